#include "app/outputs/image_scale.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace gb {

namespace {

// For each output column (or row): the two source columns it lies between and the weight of the second.
struct Tap {
  int first, second;
  float weight;
};

std::vector<Tap> tapsFor(int from, int to) {
  std::vector<Tap> taps(static_cast<size_t>(to));
  const float step = static_cast<float>(from) / static_cast<float>(to);
  for (int i = 0; i < to; ++i) {
    // The output pixel's centre in source pixel coordinates, measured from the first source centre.
    const float x = std::clamp((static_cast<float>(i) + 0.5f) * step - 0.5f, 0.0f, static_cast<float>(from - 1));
    const int first = static_cast<int>(x);
    taps[static_cast<size_t>(i)] = {first, std::min(first + 1, from - 1), x - static_cast<float>(first)};
  }
  return taps;
}

}  // namespace

std::vector<uint8_t> scaleRgb(const std::vector<uint8_t>& rgb, int width, int height, int toWidth, int toHeight) {
  if (width <= 0 || height <= 0 || toWidth <= 0 || toHeight <= 0)
    throw std::invalid_argument("scaleRgb: sizes must be positive");
  if (rgb.size() != 3ull * static_cast<size_t>(width) * static_cast<size_t>(height))
    throw std::invalid_argument("scaleRgb: the image is not width x height RGB");
  if (width == toWidth && height == toHeight) return rgb;
  const std::vector<Tap> columns = tapsFor(width, toWidth), rows = tapsFor(height, toHeight);
  std::vector<uint8_t> out(3ull * static_cast<size_t>(toWidth) * static_cast<size_t>(toHeight));
  std::vector<float> upper(3ull * static_cast<size_t>(toWidth)), lower(upper.size());
  // One source row resampled across: the columns' taps applied to each channel.
  auto spreadRow = [&](int row, std::vector<float>& into) {
    const uint8_t* source = rgb.data() + 3ull * static_cast<size_t>(row) * static_cast<size_t>(width);
    for (size_t x = 0; x < columns.size(); ++x) {
      const Tap& t = columns[x];
      for (size_t c = 0; c < 3; ++c) {
        const float a = source[3 * static_cast<size_t>(t.first) + c], b = source[3 * static_cast<size_t>(t.second) + c];
        into[3 * x + c] = a + t.weight * (b - a);
      }
    }
  };
  int inUpper = -1, inLower = -1;  // the source rows spread into `upper` and `lower`: neighbours share them
  for (size_t y = 0; y < rows.size(); ++y) {
    const Tap& t = rows[y];
    if (t.first == inLower) {
      std::swap(upper, lower);
      std::swap(inUpper, inLower);
    }
    if (t.first != inUpper) spreadRow(inUpper = t.first, upper);
    if (t.second != inLower) spreadRow(inLower = t.second, lower);
    uint8_t* target = out.data() + 3 * y * static_cast<size_t>(toWidth);
    for (size_t i = 0; i < upper.size(); ++i)
      target[i] = static_cast<uint8_t>(upper[i] + t.weight * (lower[i] - upper[i]) + 0.5f);  // both in 0..255
  }
  return out;
}

}  // namespace gb
