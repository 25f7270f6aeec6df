#pragma once
// PNG files through libpng: 8-bit RGB images, rows from the top.

#include <cstdint>
#include <filesystem>
#include <vector>

namespace gb {

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  // 3 bytes per pixel, row-major from the top
};

// Written atomically (output_file.h); OutputError naming the file when it cannot be.
void writePng(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& rgb);
// The largest side readPng accepts: an environment map of 16384 x 8192 is already 400 MB of RGB.
inline constexpr unsigned kMaxPngSide = 16384;

// Any PNG (palette, grey, alpha, 16-bit) converted to 8-bit RGB; throws with the file's name when it cannot,
// or when its header claims more than kMaxPngSide pixels on a side (checked before anything is allocated).
RgbImage readPng(const std::filesystem::path& path);

}  // namespace gb
