#include "host/banner_text.h"

#include <algorithm>
#include <sstream>

#include "host/bitmap_font.h"

namespace gb {

namespace {

// sRGB-encoded colours (the output image's encoding): warm white text on a near-black band, legible over sky,
// ground and film alike.
constexpr uint8_t kInk[4] = {255, 244, 214, 255};
constexpr uint8_t kBand[4] = {18, 18, 26, 255};

constexpr int kLinesPerScale = 180;  // image rows per unit of glyph scale: 1 at 320x240, 4 at 1280x720 (letters
                                     // 5% of the picture high, as subtitles, to be read across a room)
constexpr int kCharGap = 1;          // font pixels between characters
constexpr int kLineGap = 2;          // font pixels between lines
constexpr int kPadding = 3;          // font pixels between the text and the band's edges

void appendWordPieces(const std::string& word, size_t columns, std::vector<std::string>& lines) {
  for (size_t at = 0; at < word.size(); at += columns) lines.push_back(word.substr(at, columns));
}

void cutWithEllipsis(std::string& line, size_t columns) {
  const std::string ellipsis = "...";
  if (columns < ellipsis.size()) return;
  line = line.substr(0, std::min(line.size(), columns - ellipsis.size())) + ellipsis;
}

void fill(BannerImage& banner, int x, int y, int size, const uint8_t colour[4]) {
  for (int dy = 0; dy < size; ++dy)
    for (int dx = 0; dx < size; ++dx) {
      const int px = x + dx, py = y + dy;
      if (px < 0 || px >= banner.width || py < 0 || py >= banner.height) continue;
      std::copy(colour, colour + 4, banner.rgba.begin() + 4 * (static_cast<ptrdiff_t>(py) * banner.width + px));
    }
}

}  // namespace

std::vector<std::string> wrapBannerLines(const std::string& text, size_t columns, size_t maxLines) {
  std::vector<std::string> lines;
  if (columns == 0 || maxLines == 0) return lines;
  std::istringstream words(text);
  std::string word, line;
  bool cut = false;
  while (words >> word) {
    if (!line.empty() && line.size() + 1 + word.size() <= columns) {
      line += " " + word;
      continue;
    }
    if (!line.empty()) lines.push_back(line);
    line.clear();
    if (word.size() <= columns) {
      line = word;
    } else {
      appendWordPieces(word, columns, lines);
      line = lines.back();
      lines.pop_back();
    }
    if (lines.size() >= maxLines) {
      cut = true;
      break;
    }
  }
  if (!line.empty() && lines.size() < maxLines) lines.push_back(line);
  if (lines.size() > maxLines) {
    lines.resize(maxLines);
    cut = true;
  }
  if (cut && !lines.empty()) cutWithEllipsis(lines.back(), columns);
  return lines;
}

BannerImage drawBanner(const std::string& text, int imageWidth, int imageHeight) {
  BannerImage banner;
  if (imageWidth <= 0 || imageHeight <= 0) return banner;
  const int scale = std::max(1, imageHeight / kLinesPerScale);
  const int cellWidth = (kGlyphWidth + kCharGap) * scale;
  const int lineHeight = (kGlyphHeight + kLineGap) * scale;
  const int padding = kPadding * scale;
  const int columns = (imageWidth - 2 * padding + kCharGap * scale) / cellWidth;
  const int fitLines = (imageHeight - 2 * padding) / lineHeight;
  if (columns <= 0 || fitLines <= 0) return banner;
  const std::vector<std::string> lines =
      wrapBannerLines(text, static_cast<size_t>(columns), std::min(kMaxBannerLines, static_cast<size_t>(fitLines)));
  if (lines.empty()) return banner;

  banner.width = imageWidth;
  banner.height = static_cast<int>(lines.size()) * lineHeight - kLineGap * scale + 2 * padding;
  banner.rgba.resize(4 * static_cast<size_t>(banner.width) * static_cast<size_t>(banner.height));
  for (size_t p = 0; p < banner.rgba.size(); p += 4) std::copy(kBand, kBand + 4, banner.rgba.begin() + p);
  for (size_t l = 0; l < lines.size(); ++l) {
    const std::string& line = lines[l];
    const int lineWidth = static_cast<int>(line.size()) * cellWidth - kCharGap * scale;
    const int x0 = (imageWidth - lineWidth) / 2, y0 = padding + static_cast<int>(l) * lineHeight;
    for (size_t i = 0; i < line.size(); ++i)
      for (int gy = 0; gy < kGlyphHeight; ++gy)
        for (int gx = 0; gx < kGlyphWidth; ++gx)
          if (glyphInk(line[i], gx, gy))
            fill(banner, x0 + static_cast<int>(i) * cellWidth + gx * scale, y0 + gy * scale, scale, kInk);
  }
  return banner;
}

}  // namespace gb
