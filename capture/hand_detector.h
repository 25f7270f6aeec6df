#pragma once
// Hands from a depth frame, without a skeleton tracker (libfreenect gives depth only):
//   1. segment the performer: the nearest large connected region inside a depth band;
//   2. find the hands: the (at most two) extremities of that region nearest the camera that stand out in
//      front of the body, at least minHandSeparation apart;
//   3. place each hand at the centroid of the performer's points around its extremity, pushed back from
//      the visible surface to the hand's centre, in camera space (kinect_depth.h intrinsics);
//   4. keep each hand's identity over time (HandTracker): nearest to where it was, never a jump further
//      than a hand can move, left and right by side only when a hand is first found.
// docs/capture.md describes the method and what it cannot see.

#include <optional>
#include <vector>

#include "hand_source.h"
#include "kinect_depth.h"

namespace gb {

struct DetectionOptions {
  float nearLimit = 0.5f;           // depth band (m): nearer pixels are ignored (the Kinect sees nothing nearer
  float farLimit = 3.0f;            //   than ~0.5 m); farther ones too (keep the back wall out)
  int minPerformerPixels = 3000;    // smallest region taken for a person (a body at 3 m covers ~20000 pixels)
  float depthJump = 0.06f;          // neighbouring pixels further apart in depth (m) belong to different regions
  float minExtension = 0.15f;       // a hand stands at least this far in front of the body's median depth (m)
  float extremityRadius = 0.08f;    // an extremity is the nearest point of the region within this radius (m)
  float minHandSeparation = 0.12f;  // two extremities closer than this (m) are one hand
  float handRadius = 0.09f;         // region points within this distance (m) of the extremity form the hand
  float surfaceToCentre = 0.02f;    // the hand's centre lies this far behind its visible surface's centroid (m)
};

struct DetectedHand {
  Vec3d position;  // camera space (m)
  int pixels = 0;  // region points that made it
};

struct Detection {
  std::vector<DetectedHand> hands;  // 0, 1 or 2, nearest first
  int performerPixels = 0;          // 0: nobody in the band
  double bodyDepth = 0.0;           // median depth of the performer (m)
  double bodyCentreX = 0.0;         // camera-space x of the performer's centroid at bodyDepth (m)
};

Detection detectHands(const kinect::DepthFrame& frame, const DetectionOptions& options);

struct TrackerOptions {
  bool mirrored = false;      // the depth image is mirrored (the performer's left hand on the image's left)
  double maxHandSpeed = 6.0;  // m/s: a detection further than this allows from a hand's last position is not it
  double jumpMargin = 0.10;   // m, added to that distance (detection noise)
  double holdTime = 0.5;      // s, confidence decay while a hand is not seen (HandHold)
};

// Left/right identity over time. New detections go to the existing hands by least total distance, each
// within reach of where that hand was last seen; a hand with no detection is held (HandHold).
class HandTracker {
 public:
  explicit HandTracker(const TrackerOptions& options = {});
  HandSample update(double time, const Detection& detection);

 private:
  TrackerOptions options_;
  std::optional<Vec3d> last_[2];
  double lastSeen_[2] = {0.0, 0.0};
  HandHold hold_[2];
  [[nodiscard]] bool withinReach(int hand, double time, const Vec3d& p) const;
  [[nodiscard]] bool onLeftSide(const Vec3d& p, double bodyCentreX) const;
};

}  // namespace gb
