// How colourful rendered frames are, as an audience sees a soap film: the share of each image's pixels in vivid
// colour, and of those the greens and magentas a soap film is known by (docs/performance.md, "the main job's
// colour"). Prints a line per image, then the most colourful.
//   ./build/bench/gb_colour_bench out/render_*.png
//
// A pixel is vivid where its HSV saturation is over 0.3 and its value over 0.35 (8-bit sRGB as written), unless it is
// the wands' wood: hue 15-45 degrees below value 0.78. Green is hue 90-160 degrees, magenta 280-340. The bare
// environment counts too (the default sky's blue is vivid: 0.020 of the image), so compare frames of one camera.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "capture/png_image.h"

namespace {

struct ColourShares {
  double vivid = 0, green = 0, magenta = 0;  // of the image's pixels
};

// Hue in degrees [0, 360) of an 8-bit RGB pixel whose largest and smallest channels differ.
double hueOf(double r, double g, double b, double largest, double spread) {
  double h = 0;
  if (largest == r)
    h = (g - b) / spread;
  else if (largest == g)
    h = 2.0 + (b - r) / spread;
  else
    h = 4.0 + (r - g) / spread;
  h *= 60.0;
  return h < 0 ? h + 360.0 : h;
}

ColourShares sharesOf(const gb::RgbImage& image) {
  ColourShares c;
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  size_t vivid = 0, green = 0, magenta = 0;
  for (size_t p = 0; p < pixels; ++p) {
    const double r = image.rgb[3 * p], g = image.rgb[3 * p + 1], b = image.rgb[3 * p + 2];
    const double largest = std::max({r, g, b}), spread = largest - std::min({r, g, b});
    const double value = largest / 255.0;
    if (!(value > 0.35) || !(spread / largest > 0.3)) continue;
    const double hue = hueOf(r, g, b, largest, spread);
    if (hue >= 15.0 && hue <= 45.0 && value < 0.78) continue;  // the wands' wood
    ++vivid;
    if (hue >= 90.0 && hue <= 160.0) ++green;
    if (hue >= 280.0 && hue <= 340.0) ++magenta;
  }
  const auto share = [&](size_t n) { return pixels ? static_cast<double>(n) / static_cast<double>(pixels) : 0.0; };
  return {share(vivid), share(green), share(magenta)};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s IMAGE.png ...\n", argv[0]);
    return 2;
  }
  std::string best;
  ColourShares most;
  for (int a = 1; a < argc; ++a) {
    try {
      const ColourShares c = sharesOf(gb::readPng(argv[a]));
      std::printf("%s: vivid %.4f, green %.4f, magenta %.4f\n", argv[a], c.vivid, c.green, c.magenta);
      if (best.empty() || c.vivid > most.vivid) best = argv[a], most = c;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gb_colour_bench: %s\n", e.what());
      return 1;
    }
  }
  std::printf("most colourful: %s (vivid %.4f, green %.4f, magenta %.4f)\n", best.c_str(), most.vivid, most.green,
              most.magenta);
  return 0;
}
