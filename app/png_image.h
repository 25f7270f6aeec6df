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

void writePng(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& rgb);
// Any PNG (palette, grey, alpha, 16-bit) converted to 8-bit RGB; throws with the file's name when it cannot.
RgbImage readPng(const std::filesystem::path& path);

}  // namespace gb
