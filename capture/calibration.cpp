#include "capture/calibration.h"

#include <cmath>
#include <numbers>

namespace gb {

namespace {

// Level camera coordinates: a camera pitched up by `degrees` sees a level point straight ahead below its axis.
Eigen::Matrix3d levelling(double degrees) {
  return Eigen::AngleAxisd(-degrees * std::numbers::pi / 180.0, Vec3d::UnitX()).toRotationMatrix();
}

Eigen::Matrix3d linearPart(const Calibration& c) {
  return c.reach * Vec3d(-1.0, 1.0, -1.0).asDiagonal() * levelling(c.cameraPitch);
}

}  // namespace

Vec3d Calibration::toWorld(const Vec3d& camera) const { return anchor + linearPart(*this) * (camera - performer); }

Vec3d Calibration::velocityToWorld(const Vec3d& cameraVelocity) const { return linearPart(*this) * cameraVelocity; }

Vec3d Calibration::toCamera(const Vec3d& world) const {
  return performer + linearPart(*this).inverse() * (world - anchor);
}

Vec3d Calibration::restHand(Hand hand) const {
  const double side = hand == Hand::Left ? -0.5 : 0.5;
  return toCamera(anchor + Vec3d(side * restSeparation, 0.0, 0.0));
}

}  // namespace gb
