#include "app/show/mirror_view.h"

#include <algorithm>
#include <cmath>

#include "app/show/performer_view.h"
#include "capture/colour_registration.h"

namespace gb {

DepthCameraView mirrorCamera(const Calibration& calibration) {
  // toCamera is affine: its linear part the inverse of the one velocities map by (the same while the calibration
  // glides after the performer, so the sky drawn with it is drawn once), then where the world's origin lands.
  Eigen::Matrix3d toWorld;
  for (int axis = 0; axis < 3; ++axis) toWorld.col(axis) = calibration.velocityToWorld(Vec3d::Unit(axis));
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = toWorld.inverse();
  m.block<3, 1>(0, 3) = calibration.toCamera(Vec3d::Zero());
  DepthCameraView view;
  view.worldToCamera = m.cast<float>();
  view.fx = static_cast<float>(kinect::kFx);
  view.fy = static_cast<float>(kinect::kFy);
  view.cx = static_cast<float>(kinect::kCx);
  view.cy = static_cast<float>(kinect::kCy);
  view.imageWidth = kinect::kWidth;
  view.imageHeight = kinect::kHeight;
  view.mirrored = true;
  return view;
}

namespace {

uint32_t packRgba(double r, double g, double b) {
  const auto byte = [](double c) { return static_cast<uint32_t>(std::lround(255.0 * std::clamp(c, 0.0, 1.0))); };
  return byte(r) | byte(g) << 8 | byte(b) << 16 | 255u << 24;
}

// The depth of the drawn pixels averaged over a square of 2 r + 1 pixels (0 where nothing is drawn): a real
// camera's depth comes in steps of 1-3 cm, whose slopes would shade as contour lines.
// Only the rows [top, bottom) and columns [left, right) hold drawn pixels.
struct Box {
  int left = kinect::kWidth, top = kinect::kHeight, right = 0, bottom = 0;
  void add(int u, int v) {
    left = std::min(left, u), right = std::max(right, u + 1), top = std::min(top, v), bottom = std::max(bottom, v + 1);
  }
};

std::vector<float> smoothedDepth(const std::vector<float>& depth, int r, const Box& box) {
  const int w = kinect::kWidth, h = kinect::kHeight;
  std::vector<float> sum(depth.size(), 0.0f), count(depth.size(), 0.0f), out(depth.size(), 0.0f);
  for (int v = std::max(0, box.top - r); v < std::min(h, box.bottom + r); ++v)  // across the rows, then down
    for (int u = box.left; u < box.right; ++u)
      for (int k = std::max(0, u - r); k <= std::min(w - 1, u + r); ++k) {
        const float z = depth[static_cast<size_t>(v * w + k)];
        sum[static_cast<size_t>(v * w + u)] += z;
        count[static_cast<size_t>(v * w + u)] += z > 0.0f ? 1.0f : 0.0f;
      }
  for (int v = box.top; v < box.bottom; ++v)
    for (int u = box.left; u < box.right; ++u) {
      const size_t i = static_cast<size_t>(v * w + u);
      if (!(depth[i] > 0.0f)) continue;
      float s = 0.0f, n = 0.0f;
      for (int k = std::max(0, v - r); k <= std::min(h - 1, v + r); ++k) {
        s += sum[static_cast<size_t>(k * w + u)];
        n += count[static_cast<size_t>(k * w + u)];
      }
      out[i] = s / n;
    }
  return out;
}

// Lambert shading of the surface the (smoothed) depth shows at pixel (u, v), under a light from above the camera:
// its normal from the slope of the depth across the neighbours `step` pixels off that are drawn too (flat where
// none is).
double shade(const std::vector<float>& depth, int u, int v, int step) {
  const size_t i = static_cast<size_t>(v) * kinect::kWidth + static_cast<size_t>(u);
  const float z = depth[i];
  const auto at = [&](int du, int dv) {
    const int x = u + du, y = v + dv;
    if (x < 0 || y < 0 || x >= kinect::kWidth || y >= kinect::kHeight) return z;
    const float n = depth[static_cast<size_t>(y) * kinect::kWidth + static_cast<size_t>(x)];
    return n > 0.0f && std::abs(n - z) < 0.1f ? n : z;  // across an edge: flat
  };
  // Metres of depth per metre across, along the image's x (right) and y (down).
  const double gx = (at(step, 0) - at(-step, 0)) * kinect::kFx / (2.0 * step * z);
  const double gy = (at(0, step) - at(0, -step)) * kinect::kFy / (2.0 * step * z);
  const Vec3d normal = Vec3d(gx, -gy, -1.0).normalized();  // camera space (y up), facing the camera
  const Vec3d light = Vec3d(0.0, 0.5, -1.0).normalized();
  return 0.35 + 0.65 * std::max(0.0, normal.dot(light));
}

}  // namespace

CameraImage cameraImageOf(const kinect::DepthFrame& frame, const BodyDepth& body, bool room) {
  CameraImage image;
  image.width = kinect::kWidth;
  image.height = kinect::kHeight;
  image.depth.assign(static_cast<size_t>(kinect::kPixels), 0.0f);
  image.rgba.assign(static_cast<size_t>(kinect::kPixels), 0u);
  const std::array<float, 2048>& metres = kinect::depthTable();
  std::vector<uint8_t> performer(static_cast<size_t>(kinect::kPixels), 0);
  Box drawn;
  for (int v = 0; v < kinect::kHeight; ++v)
    for (int u = 0; u < kinect::kWidth; ++u) {
      const size_t i = static_cast<size_t>(v) * kinect::kWidth + static_cast<size_t>(u);
      const float z = metres[frame.raw[i] & 2047];
      if (!(z > 0.0f)) continue;
      // The segmentation's grid point of this pixel, and this pixel near its depth: the performer's.
      const float bodyZ = body.at(u / 2, v / 2);
      performer[i] = bodyZ < BodyDepth::kBackground && std::abs(z - bodyZ) < 0.15f;
      if (!performer[i] && !room) continue;
      image.depth[i] = z;
      drawn.add(u, v);
    }
  const bool colour = frame.colour.size() == static_cast<size_t>(kinect::kColourBytes) && frame.registration;
  const std::vector<float> smooth = colour ? std::vector<float>() : smoothedDepth(image.depth, 3, drawn);
  const std::vector<uint8_t> registered =
      colour ? registeredColour(frame.colour, image.depth, *frame.registration) : std::vector<uint8_t>();
  for (int v = drawn.top; v < drawn.bottom; ++v)
    for (int u = drawn.left; u < drawn.right; ++u) {
      const size_t i = static_cast<size_t>(v) * kinect::kWidth + static_cast<size_t>(u);
      if (!(image.depth[i] > 0.0f)) continue;
      if (colour) {
        image.rgba[i] =
            packRgba(registered[3 * i] / 255.0, registered[3 * i + 1] / 255.0, registered[3 * i + 2] / 255.0);
        continue;
      }
      const double light = shade(smooth, u, v, 2);
      image.rgba[i] = performer[i] ? packRgba(0.93 * light, 0.80 * light, 0.68 * light)   // a warm silhouette
                                   : packRgba(0.45 * light, 0.47 * light, 0.50 * light);  // the room, grey
    }
  return image;
}

std::string MirrorView::toggle() {
  on_ = !on_;
  if (on_ && !source_) return "mirror view: on, shown with a depth camera input (kinect, fakenect:DIR)";
  return on_ ? "mirror view: on" : "mirror view: off (the virtual stage)";
}

void MirrorView::apply(RenderFrame& frame, const Calibration* calibration) {
  if (!on_ || !source_ || !calibration || !source_->hasDepth()) return;
  if (std::optional<ObservedHandSource::Frame> newest = source_->takeFrame())
    image_ = cameraImageOf(newest->depth, newest->body, room_);
  camera_ = mirrorCamera(*calibration);
  frame.mirror = &camera_;
  frame.cameraImage = image_.depth.empty() ? nullptr : &image_;
}

}  // namespace gb
