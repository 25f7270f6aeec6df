#pragma once
// Hands from a depth frame, without a skeleton tracker (libfreenect gives depth only):
//   1. the performer's pixels (performer_segmentation.h): the floor and the room dropped, the person in front
//      taken among the bodies left;
//   2. which of them are a hand, the performer's left or right (hand_forest.h): a randomized decision forest
//      over depth-comparison features, as the Kinect SDK's skeleton tracker finds body parts, trained on real
//      Kinect depth;
//   3. where each hand is: the modes of its pixels' density over the surface (mean shift), pushed back from
//      the surface to the hand's centre;
//   4. identity over time (HandTracker): each hand takes the mode of its side where it was going, else its
//      side's strongest mode when that is sure.
// docs/capture.md describes the method, how it was trained and judged, and what it cannot see.

#include <optional>
#include <string>
#include <vector>

#include "capture/floor_plane.h"
#include "capture/hand_forest.h"
#include "capture/hand_source.h"
#include "capture/kinect_depth.h"
#include "capture/performer_segmentation.h"

namespace gb {

struct DetectionOptions {
  SegmentationOptions segmentation;
  const HandForest* forest = nullptr;  // the hand forest; nullptr: HandForest::builtin()
  ModeOptions modes;
};

// A hand found in one frame. side: +1 when it is the forest's left hand (the camera's +x side of a performer
// facing an unmirrored camera), -1 its right hand.
struct DetectedHand {
  Vec3d position;           // camera space (m): the hand's centre
  double confidence = 1.0;  // 0..1: how much sure hand surface is around it (a whole hand: 1)
  int side = 0;
  double sideConfidence = 0.0;  // 0..1: how much more of its hand surface is of its side than of the other
};

struct Detection {
  std::vector<DetectedHand> hands;  // every hand mode of either side, most confident first
  int performerPixels = 0;          // 0: nobody taken for the performer (full-resolution pixels)
  double bodyDepth = 0.0;           // median depth of the performer (m)
  std::optional<Vec3d> centre;      // the performer's median point (camera space)
  std::optional<FloorPlane> floor;  // the floor when in view
  BodyDepth body;                   // the performer's depth on the half-resolution grid (0 elsewhere)
  std::string why;                  // which body was taken for the performer and why, or why none was
  std::string advice;               // what the performer should change to be found (empty: nothing)
};

// A hand mode in the image's lowest rows (a fifth) on a limb that runs out of the image there is a leg more often than
// a hand: close to the camera, with the legs cut off by the lower edge, thighs and knees end there as forearms do at
// the hands, and a hand held that low is usually out of the image. Its confidence is multiplied by this, so that the
// tracker takes it for a hand it was already following there but not for a new one (TrackerOptions).
inline constexpr double kLimbAtEdgeFactor = 0.5;
double lowerEdgeFactor(const BodyDepth& body, const Vec3d& hand);  // kLimbAtEdgeFactor there, else 1

// Hands of the performer that `segmenter` takes in this frame (it learns the room as it goes).
Detection detectHands(const kinect::DepthFrame& frame, PerformerSegmenter& segmenter, const DetectionOptions& options);
// One frame on its own: a room never seen before.
Detection detectHands(const kinect::DepthFrame& frame, const DetectionOptions& options);

struct TrackerOptions {
  bool mirrored = false;          // the depth image is mirrored (the performer's left hand on the image's left)
  double holdTime = 0.5;          // s, confidence decay while a hand is not seen (HandHold)
  double newConfidence = 0.6;     // a hand not followed is taken from this confidence
  double followConfidence = 0.3;  // a followed hand from this, near where it was going
  double followTime = 0.3;        // s: a hand seen this recently is followed
  double maxHandSpeed = 4.0;      // m/s: a followed hand's detection within this speed of its prediction is near
  double jumpMargin = 0.10;       // m, added to that distance (detection noise)
  // A followed hand whose detection is this many times weaker than a sure detection of its side elsewhere, frame
  // after frame, is let go for that one: the detections no longer support where it is (a hand followed onto a knee
  // while the raised hand is found).
  double letGoRatio = 2.0;
  int letGoFrames = 3;
};

// Left/right identity over time. The forest tells the sides (it learned them from whole bodies, crossed arms
// included), so each hand takes a detection of its side: a followed hand the one nearest to where it was
// going, from a lower confidence; else (a new hand, or a followed one with nothing of its side near, or one whose
// detection a sure one elsewhere has outweighed for letGoFrames) the strongest, only when it is sure. A hand with no
// detection is held (HandHold).
class HandTracker {
 public:
  explicit HandTracker(const TrackerOptions& options = {});
  HandSample update(double time, const Detection& detection);

 private:
  TrackerOptions options_;
  std::optional<Vec3d> last_[2];
  Vec3d velocity_[2] = {Vec3d::Zero(), Vec3d::Zero()};
  double lastSeen_[2] = {0.0, 0.0};
  int unsupported_[2] = {0, 0};  // frames in a row a sure detection elsewhere outweighed the followed one
  HandHold hold_[2];
  [[nodiscard]] Vec3d predicted(int hand, double time) const;
  [[nodiscard]] bool followed(int hand, double time) const;
  [[nodiscard]] int sideOf(int hand) const;  // the DetectedHand::side of that hand
  // How far from where a followed hand was going its detection may lie (m).
  [[nodiscard]] double reach(int hand, double time) const;
  // Whether hand h takes detection d now.
  [[nodiscard]] bool takes(int hand, double time, const DetectedHand& d) const;
  void record(int hand, double time, const Vec3d& p);
};

}  // namespace gb
