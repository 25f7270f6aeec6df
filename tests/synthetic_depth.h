#pragma once
// Synthetic Kinect v1 depth frames of a performer, for the detection and fakenect tests: a torso box, a
// head, two arms of spheres from the shoulders to the hands, spherical hands, and a back wall, ray cast
// through the Kinect depth intrinsics and quantised to raw 11-bit disparity with the inverse of the fit the
// detector uses.

#include <optional>

#include "hand_source.h"
#include "kinect_depth.h"

namespace gb::test {

struct SyntheticPerformer {
  std::optional<Vec3d> leftHand = Vec3d(0.25, 0.05, 1.9);  // hand centres, camera space (m); nullopt: arm down
  std::optional<Vec3d> rightHand = Vec3d(-0.25, 0.0, 1.85);
  Vec3d torso = Vec3d(0.0, -0.1, 2.45);  // centre of the torso box (0.4 x 0.7 x 0.2 m)
  double handRadius = 0.045;
  double wallDepth = 3.6;  // beyond the detector's default far limit
};

kinect::DepthFrame renderPerformer(const SyntheticPerformer& performer, double time = 0.0, uint32_t timestamp = 0);

// A few seconds of two hands moving: the hands of the synthetic session at time t (camera space).
SyntheticPerformer sessionPose(double t);

}  // namespace gb::test
