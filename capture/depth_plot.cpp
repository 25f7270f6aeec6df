#include "capture/depth_plot.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gb {

namespace {

using kinect::kHeight;
using kinect::kWidth;

// A picture of the camera's image at 1/step of its resolution, drawn on in the camera's pixel coordinates.
struct Canvas {
  explicit Canvas(int every) : step(every), width(kWidth / every), height(kHeight / every) {
    rgb.assign(static_cast<size_t>(width) * height * 3, 0);
  }
  int step, width, height;
  std::vector<uint8_t> rgb;
  void set(int u, int v, uint8_t r, uint8_t g, uint8_t b) {
    if (u < 0 || v < 0) return;
    u /= step, v /= step;
    if (u >= width || v >= height) return;
    uint8_t* p = &rgb[(static_cast<size_t>(v) * width + u) * 3];
    p[0] = r, p[1] = g, p[2] = b;
  }
  void ring(const Vec3d& camera, int radius, uint8_t r, uint8_t g, uint8_t b) {
    if (camera.z() <= 0.0) return;
    const Eigen::Vector2d px = kinect::cameraToPixel(camera);
    for (int k = 0; k < 360; ++k)
      for (int w = 0; w < 3; ++w) {
        const double a = k * 3.14159265 / 180.0, rr = radius + w;
        set(static_cast<int>(std::lround(px.x() + rr * std::cos(a))),
            static_cast<int>(std::lround(px.y() + rr * std::sin(a))), r, g, b);
      }
  }
  void cross(const Vec3d& camera, int size, uint8_t r, uint8_t g, uint8_t b) {
    if (camera.z() <= 0.0) return;
    const Eigen::Vector2d px = kinect::cameraToPixel(camera);
    const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
    for (int k = -size; k <= size; ++k)
      for (int w = -1; w <= 1; ++w) set(u + k, v + w, r, g, b), set(u + w, v + k, r, g, b);
  }
};

}  // namespace

RgbImage drawDepthPlot(const kinect::DepthFrame& frame, const Detection& detection, const HandSample& hands, int step) {
  Canvas c(std::clamp(step, 1, 8));
  const auto& table = kinect::depthTable();
  for (int v = 0; v < kHeight; v += c.step)
    for (int u = 0; u < kWidth; u += c.step) {
      const float z = table[frame.raw[static_cast<size_t>(v) * kWidth + u] & 2047];
      if (z <= 0.0f) {
        c.set(u, v, 10, 10, 60);
        continue;
      }
      // 0.5 m white to 5 m black.
      const auto grey = static_cast<uint8_t>(std::clamp(255.0 * (1.0 - (z - 0.5) / 4.5), 0.0, 255.0));
      const Vec3d p = kinect::pixelToCamera(u, v, z);
      if (detection.floor && std::abs(detection.floor->heightOf(p)) < 0.05)
        c.set(u, v, grey / 3, static_cast<uint8_t>(std::min(255, grey / 2 + 90)), grey / 3);
      else if (detection.body.at(u / 2, v / 2) < BodyDepth::kBackground)
        c.set(u, v, static_cast<uint8_t>(std::min(255, grey / 2 + 110)), static_cast<uint8_t>(grey * 3 / 4), grey / 3);
      else
        c.set(u, v, grey, grey, grey);
    }
  if (detection.centre) c.cross(*detection.centre, 8, 0, 230, 230);
  for (const DetectedHand& h : detection.hands) c.cross(h.position, 5, 255, 255, 255);
  if (hands.left.measured) c.ring(hands.left.position, 14, 230, 40, 40);
  if (hands.right.measured) c.ring(hands.right.position, 14, 60, 90, 255);
  return {c.width, c.height, std::move(c.rgb)};
}

void writeDepthPlot(const std::filesystem::path& path, const kinect::DepthFrame& frame, const Detection& detection,
                    const HandSample& hands) {
  const RgbImage plot = drawDepthPlot(frame, detection, hands);
  writePng(path, plot.width, plot.height, plot.rgb);
}

}  // namespace gb
