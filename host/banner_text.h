#pragma once
// The live window's message banner: a status line (an unstable simulation replaced, a camera lost, an input
// that ended, nobody in front of the camera) as text on a dark band across the top of the image, drawn on
// the CPU with host/bitmap_font.h and copied into the renderer's output (host/renderer.h, RenderFrame::banner).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gb {

constexpr size_t kMaxBannerLines = 3;  // a longer message is cut, its last line ending in "..."

// A banner's pixels: RGBA, 8 bits a channel, sRGB-encoded like the renderer's output, rows from the top.
struct BannerImage {
  int width = 0;  // the image's width; 0: no banner
  int height = 0;
  std::vector<uint8_t> rgba;
};

// `text` broken at spaces into lines of at most `columns` characters (a word longer than a line is split), at
// most `maxLines` of them. Runs of spaces and line breaks count as one space.
std::vector<std::string> wrapBannerLines(const std::string& text, size_t columns, size_t maxLines);

// The banner for an image of `imageWidth` x `imageHeight` pixels: the image's width, the text centred, light on
// dark. Glyphs are scaled by imageHeight / 180 (at least 1) so they read the same at any size. Empty text, or an
// image too small for one line: a banner of height 0.
BannerImage drawBanner(const std::string& text, int imageWidth, int imageHeight);

}  // namespace gb
