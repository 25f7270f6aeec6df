#include "capture/kinect_depth.h"

#include <cmath>

namespace gb::kinect {

double rawToMetres(uint16_t raw) {
  if (raw >= kFarthestRaw) return 0.0;
  return kTanScale * std::tan(raw / kTanDivisor + kTanOffset);
}

uint16_t metresToRaw(double z) {
  if (!(z > rawToMetres(0)) || z >= rawToMetres(kFarthestRaw - 1)) return kNoReading;
  const double raw = (std::atan(z / kTanScale) - kTanOffset) * kTanDivisor;
  return static_cast<uint16_t>(std::lround(raw));
}

const std::array<float, 2048>& depthTable() {
  static const std::array<float, 2048> table = [] {
    std::array<float, 2048> t{};
    for (int raw = 0; raw < 2048; ++raw) t[raw] = static_cast<float>(rawToMetres(static_cast<uint16_t>(raw)));
    return t;
  }();
  return table;
}

Eigen::Vector3d pixelToCamera(double u, double v, double z) { return {(u - kCx) * z / kFx, -(v - kCy) * z / kFy, z}; }

Eigen::Vector2d cameraToPixel(const Eigen::Vector3d& p) {
  return {kCx + kFx * p.x() / p.z(), kCy - kFy * p.y() / p.z()};
}

std::optional<Eigen::Vector3d> accelToCameraUp(double ax, double ay, double az) {
  const Eigen::Vector3d up(-ax, ay, az);
  const double g = up.norm() / kStandardGravity;
  if (!(g > 0.5 && g < 1.5)) return std::nullopt;
  const Eigen::Vector3d unit = up.normalized();
  if (unit.y() < 0.5) return std::nullopt;  // cos 60 degrees
  return unit;
}

std::array<int16_t, 3> cameraUpToAccel(const Eigen::Vector3d& up) {
  const Eigen::Vector3d counts = kAccelCountsPerG * up.normalized();
  return {static_cast<int16_t>(std::lround(-counts.x())), static_cast<int16_t>(std::lround(counts.y())),
          static_cast<int16_t>(std::lround(counts.z()))};
}

}  // namespace gb::kinect
