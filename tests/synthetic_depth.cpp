#include "synthetic_depth.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace gb::test {

namespace {

using namespace kinect;

Vec3d ray(int u, int v) { return {(u - kCx) / kFx, -(v - kCy) / kFy, 1.0}; }  // z = 1: the hit's t is its depth

struct Canvas {
  std::vector<double> depth;

  // Pixels whose rays may hit something inside the camera-space box [lo, hi] (in front of the camera).
  template <typename Hit>
  void raster(const Vec3d& lo, const Vec3d& hi, Hit hit) {
    double u0 = kWidth, u1 = 0, v0 = kHeight, v1 = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3d p((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(), (corner & 4) ? hi.z() : lo.z());
      const Eigen::Vector2d px = cameraToPixel(p);
      u0 = std::min(u0, px.x()), u1 = std::max(u1, px.x()), v0 = std::min(v0, px.y()), v1 = std::max(v1, px.y());
    }
    for (int v = std::max(0, static_cast<int>(v0) - 1); v <= std::min(kHeight - 1, static_cast<int>(v1) + 1); ++v)
      for (int u = std::max(0, static_cast<int>(u0) - 1); u <= std::min(kWidth - 1, static_cast<int>(u1) + 1); ++u) {
        const double t = hit(ray(u, v));
        double& d = depth[static_cast<size_t>(v) * kWidth + u];
        if (t > 0 && t < d) d = t;
      }
  }

  void sphere(const Vec3d& c, double r) {
    raster(c - Vec3d::Constant(r), c + Vec3d::Constant(r), [&](const Vec3d& d) {
      const double a = d.squaredNorm(), b = d.dot(c), disc = b * b - a * (c.squaredNorm() - r * r);
      return disc < 0 ? -1.0 : (b - std::sqrt(disc)) / a;
    });
  }

  void box(const Vec3d& lo, const Vec3d& hi) {
    raster(lo, hi, [&](const Vec3d& d) {
      double near = 0.0, far = 1e9;
      for (int k = 0; k < 3; ++k) {
        double t0 = lo[k] / d[k], t1 = hi[k] / d[k];
        if (t0 > t1) std::swap(t0, t1);
        near = std::max(near, t0);
        far = std::min(far, t1);
      }
      return near <= far ? near : -1.0;
    });
  }
};

}  // namespace

kinect::DepthFrame renderPerformer(const SyntheticPerformer& p, double time, uint32_t timestamp) {
  Canvas canvas{std::vector<double>(kPixels, p.wallDepth)};
  const Vec3d half(0.2, 0.35, 0.1);
  canvas.box(p.torso - half, p.torso + half);
  canvas.sphere(p.torso + Vec3d(0.0, 0.5, 0.0), 0.11);  // head
  for (int side = 0; side < 2; ++side) {
    // The performer faces the camera: their left shoulder is on the camera's +x side.
    const Vec3d shoulder = p.torso + Vec3d(side == 0 ? 0.23 : -0.23, 0.28, 0.0);
    const std::optional<Vec3d>& hand = side == 0 ? p.leftHand : p.rightHand;
    const Vec3d wrist = hand ? Vec3d(*hand + (shoulder - *hand).normalized() * p.handRadius)
                             : Vec3d(shoulder + Vec3d(0.0, -0.6, 0.0));  // arm hanging at the side
    const int pieces = static_cast<int>((wrist - shoulder).norm() / 0.02) + 1;
    for (int i = 0; i <= pieces; ++i) canvas.sphere(shoulder + (wrist - shoulder) * i / pieces, 0.04);
    if (hand) canvas.sphere(*hand, p.handRadius);
  }
  kinect::DepthFrame frame;
  frame.time = time;
  frame.timestamp = timestamp;
  for (int i = 0; i < kPixels; ++i) frame.raw[i] = metresToRaw(canvas.depth[i]);
  return frame;
}

SyntheticPerformer sessionPose(double t) {
  const double w = 2.0 * std::numbers::pi;
  SyntheticPerformer p;
  p.leftHand = Vec3d(0.25 + 0.06 * std::sin(w * 0.5 * t), 0.05 + 0.10 * std::sin(w * 0.7 * t),
                     1.9 - 0.25 * std::sin(w * 0.25 * t));
  p.rightHand = Vec3d(-0.25 - 0.06 * std::sin(w * 0.5 * t), 0.0 + 0.10 * std::cos(w * 0.7 * t),
                      1.85 - 0.25 * std::sin(w * 0.25 * t));
  return p;
}

}  // namespace gb::test
