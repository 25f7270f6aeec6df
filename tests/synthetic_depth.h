#pragma once
// Synthetic Kinect v1 depth frames of a performer, for the detection, fakenect and benchmark code: an
// articulated body of capsules standing on a floor, ray cast through the Kinect depth intrinsics and quantised
// to raw 11-bit disparity with the inverse of the fit the detector uses; optionally furniture, a wall, a tilted
// camera and Kinect noise, shadows and holes (renderScene).

#include <optional>
#include <string>
#include <vector>

#include "capture/hand_source.h"
#include "capture/kinect_depth.h"

namespace gb::test {

// The simple scene of the fakenect and command-line tests: a level camera 1.3 m over the floor, the performer
// facing it, a wall behind, no noise. Hands are given in camera space.
struct SyntheticPerformer {
  std::optional<Vec3d> leftHand = Vec3d(0.25, 0.05, 2.0);  // hand centres, camera space (m); nullopt: arm down
  std::optional<Vec3d> rightHand = Vec3d(-0.25, 0.0, 1.95);
  double bodyDepth = 2.45;  // the torso's axis (m from the camera)
  double wallDepth = 3.6;
  bool present = true;  // false: the room without anybody in it
};

kinect::DepthFrame renderPerformer(const SyntheticPerformer& performer, double time = 0.0, uint32_t timestamp = 0);

// A few seconds of two hands moving: the hands of the synthetic session at time t (camera space).
SyntheticPerformer sessionPose(double t);

}  // namespace gb::test

namespace gb::test {

// A harder scene for the detector and its benchmark (bench/depth_bench.cpp): an articulated body of capsules
// standing on a floor, seen by a camera tilted down, with furniture and a wall, and Kinect v1 noise,
// quantisation and no-reading holes.
//
// Scene space: x to the camera's right, y up, floor at y = 0, z away from the camera along the floor; the
// camera stands at (0, cameraHeight, 0). The performer faces the camera, so their left hand is at +x.
struct BodyPose {
  Vec3d feet{0.0, 0.0, 2.6};  // on the floor, between the feet (scene space)
  double height = 1.75;       // m; every length scales with it
  // Hand centres relative to the point between the shoulders (scene space axes, m); the elbows bend down
  // and back, out of the body.
  Vec3d leftHand{0.2, -0.1, -0.45};
  Vec3d rightHand{-0.2, -0.1, -0.45};
  Vec3d leftElbowHint{0.3, -1.0, 0.2};  // direction the left elbow points to (scene space)
  Vec3d rightElbowHint{-0.3, -1.0, 0.2};
};

struct SceneOptions {
  double cameraPitch = 10.0;  // degrees down
  double cameraHeight = 1.2;  // m
  bool furniture = true;      // a chair and a table beside the performer
  double wallDistance = 3.6;  // m from the camera along the floor; 0: no wall
  bool noise = true;          // Kinect v1 noise, shadows and holes
  bool performer = true;      // false: the scene without the body
  unsigned seed = 1;
};

struct SyntheticScene {
  kinect::DepthFrame frame;
  Vec3d leftHand, rightHand;   // true hand centres, camera space
  Vec3d up;                    // unit vector against gravity, camera space (what the accelerometer measures)
  double floorDistance = 0.0;  // the camera's height over the floor (m)
};

// The camera's height that shows a performer standing `distance` m away from the top of the raised hands
// (2.2 m) downwards, for a camera pitched down by `pitch` degrees.
double cameraHeightFor(double pitch, double distance);

// The depth frame of a pose and the truth: hand centres (an unreachable hand is placed at full stretch
// towards its target) and gravity, in camera space.
SyntheticScene renderScene(const BodyPose& pose, const SceneOptions& options, double time = 0.0);

// Named poses of the benchmark, blended over time: "forward", "arms-out", "crossed", "together", "overhead",
// "one-arm-down".
BodyPose namedPose(const std::string& name);
BodyPose blendPoses(const BodyPose& a, const BodyPose& b, double s);  // s in [0, 1]

// The benchmark's motions, each a few seconds long and repeating, t in seconds: "forward" (hands circling in
// front, making bubbles), "arms-out" (out sideways at body depth and back), "crossing" (crossed in front of
// the chest and back, twice a cycle), "together", "overhead", "one-arm-down" (the right arm hangs; its hand
// is not expected to be found). presented(): whether a hand is expected to be found in that motion.
const std::vector<std::string>& sequenceNames();

// An empty room around the place where a performer would stand (feet `performerDepth` m in front of the camera
// along the floor), for compositing recorded performers into (tests/depth_composite.h). Layouts:
//   "living-room"  a back wall, a sofa against it behind the performer, a chair and a table beside, a side wall;
//   "office"       a far back wall with shelves, a desk in front of the performer to one side, office chairs;
//   "close-wall"   a wall half a metre behind the performer, a door frame and a coat rack beside it.
// Depth per full-resolution pixel (m, 0 for no reading), without noise.
std::vector<double> renderRoom(const std::string& layout, double performerDepth, double cameraPitch,
                               double cameraHeight);
const std::vector<std::string>& roomLayouts();

// Kinect v1's faults on a clean depth image (m per full-resolution pixel): the projector's shadow beside near
// edges, holes at depth edges and a few elsewhere, depth noise growing with the square of the depth. They
// differ with `seed`, as they do from one real frame to the next.
void addKinectNoise(std::vector<double>& depth, unsigned seed);
BodyPose sequencePose(const std::string& sequence, double t);
bool presented(const std::string& sequence, Hand hand);

}  // namespace gb::test
