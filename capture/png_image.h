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
// The largest image readPng accepts: at most kMaxPngSide on a side and kMaxPngPixels in all. An environment map of
// 8192 x 4096 is 100 MB of RGB and 400 MB as the renderer's linear floats; one of 16384 x 8192 took 6.9 GB and
// 14.5 s to load, and drew no finer at any render size up to 4K.
inline constexpr unsigned kMaxPngSide = 16384;
inline constexpr unsigned long long kMaxPngPixels = 8192ull * 4096ull;
// The largest PNG file read (a PNG of kMaxPngPixels stored without compression is 100 MB).
inline constexpr std::uintmax_t kMaxPngBytes = std::uintmax_t{256} << 20;

// Any PNG (palette, grey, alpha, 16-bit) converted to 8-bit RGB; throws with the file's name when it cannot, when it
// is no regular file (a FIFO is named, not waited on) or when its header claims more than the largest image
// (checked before anything is allocated).
RgbImage readPng(const std::filesystem::path& path);

}  // namespace gb
