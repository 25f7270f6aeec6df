#pragma once
// Hands from a depth frame, without a skeleton tracker (libfreenect gives depth only), after Plagemann,
// Ganapathi, Koller and Thrun, "Real-time identification and localization of body parts from depth images"
// (ICRA 2010), on a half-resolution grid (320 x 240):
//   1. floor: the lowest large horizontal layer along gravity (accelerometer, else a tilt search), refined by
//      a plane fit (floor_plane.h); points near or under it are dropped;
//   2. performer: the pixels in the depth band joined into connected bodies (neighbours closer than a depth
//      step); the performer is the largest body of a person's height and width, preferring the expected
//      distance;
//   3. extrema: accumulative geodesic extrema of the performer's surface graph (edges between neighbouring
//      pixels, weighted by their 3D distance) from the torso's centre: the farthest point, then the farthest
//      from the centre and every extremum found so far, and so on;
//   4. hands: the extrema far enough along the body from the centre (an arm's length), not feet (near the
//      floor), not the head (above the shoulders, central, the nearest such); each one's side is the side of
//      the torso its geodesic path leaves by, its position the centroid of the surface around its tip pushed
//      back to the hand's centre, its confidence from its geodesic length, size and side;
//   5. identity over time (HandTracker): sides from the torso, kept through crossings by motion prediction;
//      a swap costs more than a miss.
// docs/capture.md describes the method and what it cannot see.

#include <optional>
#include <vector>

#include "floor_plane.h"
#include "hand_source.h"
#include "kinect_depth.h"

namespace gb {

struct DetectionOptions {
  float nearLimit = 0.5f;          // depth band (m): the Kinect sees nothing nearer than ~0.5 m;
  float farLimit = 4.0f;           //   its depth is too coarse beyond ~4 m
  int minPerformerPixels = 3000;   // smallest body taken for a person, in full-resolution pixels
  float depthJump = 0.07f;         // neighbouring half-resolution pixels further apart (m) are not joined
  double expectedDistance = 0.0;   // m from the camera where the performer stands (0: anywhere in the band)
  std::optional<Vec3d> gravityUp;  // camera-space up when known; else the frame's accelerometer or a search
  double floorClearance = 0.07;    // m: points this close over the floor (or under it) are floor
  double minHandGeodesic = 0.45;   // m along the body from the torso's centre: nearer extrema are not hands
  double handRadius = 0.10;        // m: surface within this distance of a tip forms the hand
  double surfaceToCentre = 0.02;   // m: the hand's centre lies this far behind its visible surface
  int extrema = 10;                // accumulative geodesic extrema looked at per frame
};

// A found hand. side: +1 when its arm leaves the torso on the camera's +x side, -1 on -x, 0 unknown.
struct DetectedHand {
  Vec3d position;           // camera space (m)
  int pixels = 0;           // half-resolution surface points that made it
  double confidence = 1.0;  // 0..1
  double geodesic = 0.0;    // m along the body from the torso's centre
  int side = 0;
  double sideConfidence = 0.0;  // 0..1: how far from the torso's middle its arm leaves (full at 10 cm)
};

struct Detection {
  std::vector<DetectedHand> hands;  // 0, 1 or 2, most confident first
  int performerPixels = 0;          // 0: nobody in the band (full-resolution pixels)
  double bodyDepth = 0.0;           // median depth of the performer (m)
  double bodyCentreX = 0.0;         // camera-space x of the torso's centre (m)
  std::optional<Vec3d> centre;      // the torso's centre (camera space)
  std::optional<Vec3d> head;        // the extremum taken for the head
  std::vector<Vec3d> extrema;       // every geodesic extremum looked at, in order
  std::optional<FloorPlane> floor;  // the floor when in view
};

Detection detectHands(const kinect::DepthFrame& frame, const DetectionOptions& options);
// The floor detectHands would find along gravityUp (nothing: searched for), for checking an accelerometer.
std::optional<FloorPlane> floorOf(const kinect::DepthFrame& frame, const DetectionOptions& options,
                                  const std::optional<Vec3d>& gravityUp);

struct TrackerOptions {
  bool mirrored = false;      // the depth image is mirrored (the performer's left hand on the image's left)
  double maxHandSpeed = 6.0;  // m/s: a detection further than this allows from a hand's prediction is not it
  double jumpMargin = 0.10;   // m, added to that distance (detection noise)
  double holdTime = 0.5;      // s, confidence decay while a hand is not seen (HandHold)
  double missCost = 0.25;     // m-equivalent cost of leaving a hand without a detection
  double newHandCost = 0.15;  // cost of a hand's first sighting: never free (a known hand near its detection
                              //   keeps it), below a miss (a new hand on its own side is taken)
  double sideCost = 0.6;      // cost of giving a hand a detection whose arm leaves the torso on the other side
                              //   (> missCost: a swap costs more than a miss)
};

// Left/right identity over time. Each frame, every way of giving the detections to the two hands is costed:
// distance from where each hand is predicted to be (its last position carried on by its velocity), a miss
// for a known hand left without one, the first sighting of a hand, and the torso-side evidence against a
// hand; the cheapest wins. A hand with no detection is held (HandHold).
class HandTracker {
 public:
  explicit HandTracker(const TrackerOptions& options = {});
  HandSample update(double time, const Detection& detection);

 private:
  TrackerOptions options_;
  std::optional<Vec3d> last_[2];
  Vec3d velocity_[2] = {Vec3d::Zero(), Vec3d::Zero()};
  double lastSeen_[2] = {0.0, 0.0};
  HandHold hold_[2];
  [[nodiscard]] Vec3d predicted(int hand, double time) const;
  [[nodiscard]] int sideOf(int hand) const;  // camera-x side (+1/-1) where that hand's arm leaves the torso
  // The cost of giving detection d to hand h; infinity when out of reach.
  [[nodiscard]] double cost(int hand, double time, const DetectedHand& d, const Detection& detection) const;
};

}  // namespace gb
