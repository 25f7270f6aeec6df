#pragma once
// Scaling an 8-bit RGB image up to the size a run writes: `run` draws at a drawn scale below 1 where the renderer is
// the CPU (lavapipe), whose cost is its pixels, and writes its PNG frames and video at the size asked for.

#include <cstdint>
#include <vector>

namespace gb {

// `rgb` (width x height, 3 bytes a pixel, rows from the top) resampled to toWidth x toHeight by bilinear
// interpolation between pixel centres, the edge pixels held beyond the last centre. Throws std::invalid_argument
// when a size is not positive or `rgb` is not width x height.
std::vector<uint8_t> scaleRgb(const std::vector<uint8_t>& rgb, int width, int height, int toWidth, int toHeight);

}  // namespace gb
