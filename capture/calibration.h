#pragma once
// From camera space (kinect_depth.h: x right in the depth image, y up, z away from the camera) to the
// simulation's world (wire_frame.h: y up, floor at y = 0, the wands at rest at x = -/+0.5 m around the anchor,
// a stroke carrying them towards +z).
//
// The performer faces the camera, so their left is the camera's +x and their forward is the camera's -z:
//   world = anchor + reach * diag(-1, 1, -1) * (level(p) - level(performer))
// where level() undoes a camera pitched up by cameraPitch degrees (rotation about the camera's x axis).
// Velocities map with the same linear part. docs/capture.md explains how to set each field.

#include "capture/hand_source.h"
#include "model/wire_frame.h"

namespace gb {

struct Calibration {
  Vec3d performer{0.0, 0.0, 2.0};  // camera-space point (m) between the performer's hands held forward at rest
  bool autoPerformer = false;      // take `performer` from the first sample with both hands (their midpoint)
  Vec3d anchor{0.0, 1.6, 0.0};     // world point `performer` maps to: the centre between the resting wand tips
  double reach = 2.0;              // world metres per metre of hand motion (a 0.6 m push becomes a 1.2 m stroke)
  double cameraPitch = 0.0;        // degrees the camera is tilted up (libfreenect leaves the motor alone)
  double restSeparation = 1.0;     // world distance between the wand tips before any hand is seen (m)

  [[nodiscard]] Vec3d toWorld(const Vec3d& camera) const;
  [[nodiscard]] Vec3d velocityToWorld(const Vec3d& cameraVelocity) const;
  [[nodiscard]] Vec3d toCamera(const Vec3d& world) const;  // the inverse of toWorld
  // Where a hand never seen yet is held (camera space): the resting wand tip of that side.
  [[nodiscard]] Vec3d restHand(Hand hand) const;
};

}  // namespace gb
