#pragma once
// Who the performer is in a depth frame of a real room, and which of its pixels are theirs.
//
// On a half-resolution grid (each 2 x 2 block's first reading inside the depth band):
//   1. floor: the lowest large horizontal layer along gravity (accelerometer, else a tilt search), refined by a
//      plane fit (floor_plane.h); points near or under it are dropped;
//   2. room: what stays where it is is the room. The segmenter learns each grid point's depth over the
//      frames, never where the performer is or was in the last 3 s, and takes a nearer surface that stays for
//      seconds as the room too (a chair moved); a point at or behind the learned room is dropped;
//   3. bodies: the points left, joined into connected bodies (neighbours closer than a few depth steps);
//   4. performer: of the bodies of a person's size (a person cut off by the image's edges included; a wall, a
//      flat or a low piece of furniture not), the one in front: nearest, moving, the one taken before, not a
//      body cut off at the image's side edge (someone passing by), near the expected distance when one is
//      given. A body taken that has not moved for kStillForRoom frames is learned as the room (a coat rack
//      is not a performer for long);
//   5. pieces of the performer the grid did not join (a forearm pointing at the camera, seen end-on as a few
//      depth steps) are bridged to the body.
// Each frame says which body was taken and why, and what to change when nobody could be (Segmentation).

#include <optional>
#include <string>
#include <vector>

#include "capture/floor_plane.h"
#include "capture/hand_forest.h"
#include "capture/kinect_depth.h"

namespace gb {

struct SegmentationOptions {
  float nearLimit = 0.5f;          // depth band (m): the Kinect sees nothing nearer than ~0.5 m;
  float farLimit = 4.0f;           //   its depth is too coarse beyond ~4 m
  double minBodyArea = 0.06;       // m^2 of surface: smaller bodies are not a person (a torso alone is ~0.2)
  double expectedDistance = 0.0;   // m from the camera where the performer stands (0: anywhere in the band)
  std::optional<Vec3d> gravityUp;  // camera-space up when known; else the frame's accelerometer or a search
  double floorClearance = 0.07;    // m: points this close over the floor (or under it) are floor
};

// One connected body of the frame, measured.
struct BodyCandidate {
  double depth = 0.0;    // median depth (m)
  double area = 0.0;     // m^2 of surface facing the camera
  double height = 0.0;   // m along up, of what is in view
  double width = 0.0;    // m across
  double moving = 0.0;   // share of its points whose depth changed in the last third of a second
  double flat = 0.0;     // share of its points within 3 cm of its best plane
  double overlap = 0.0;  // share of its points that were the performer's in the frame before (not farther)
  bool cutAbove = false, cutBelow = false, cutSide = false;  // touches the image's edge there
  Vec3d centre = Vec3d::Zero();                              // median point
  std::string rejected;                                      // why it cannot be the performer (empty when it can)
  double score = 0.0;                                        // the performer is the candidate with the highest score
  std::vector<int> nodes;                                    // grid points (v * 320 + u)
};

struct Segmentation {
  std::optional<FloorPlane> floor;
  std::vector<BodyCandidate> candidates;  // every body of at least minBodyArea, largest first
  int performer = -1;                     // index into candidates; -1: nobody
  BodyDepth body;                         // the performer's depth (bridged pieces included), 0 elsewhere
  double roomLearned = 0.0;               // share of the grid whose room depth is known
  std::string why;                        // which body was taken and why, or why none was
  std::string advice;                     // what to change to be found (empty when all is well)
};

// The depth band and floor of one frame on the detector's grid, for checking the accelerometer's gravity.
std::optional<FloorPlane> floorOf(const kinect::DepthFrame& frame, const SegmentationOptions& options,
                                  const std::optional<Vec3d>& gravityUp);

struct DepthGrid;  // the half-resolution grid of a frame's readings (performer_segmentation.cpp)

// The segmentation over time: it learns the room and remembers the performer of the frame before.

class PerformerSegmenter {
 public:
  explicit PerformerSegmenter(const SegmentationOptions& options = {});
  Segmentation segment(const kinect::DepthFrame& frame);
  [[nodiscard]] const SegmentationOptions& options() const { return options_; }

 private:
  // The parts of segment(), in order: the floor and the learned room taken out of the grid (returns the share of
  // the grid the room is learned at), the likeliest body taken as the performer, the room learned from the rest.
  double clearFloorAndRoom(DepthGrid& g, const std::optional<FloorPlane>& floor) const;
  void takePerformer(const DepthGrid& g, Segmentation& s);
  void learnRoom(const DepthGrid& sampled);

  SegmentationOptions options_;
  // The room's depth per grid point (0: not learned), the frames it has been seen there, and a nearer surface
  // that may become the room if it stays.
  std::vector<float> room_, nearer_;
  std::vector<uint16_t> seen_, nearerFrames_;
  // The depth a third of a second ago (renewed every kMotionFrames frames), against which bodies are moving.
  std::vector<float> reference_;
  int frame_ = 0;
  std::vector<uint8_t> performer_;        // the grid points of the performer in the frame before
  std::vector<float> performerDepth_;     // and their depth there (0 elsewhere)
  std::vector<uint16_t> sincePerformer_;  // frames since the performer was last at (or beside) each point
  int stillFrames_ = 0;                   // frames the performer has not moved (a body that never moves is the room)
};

}  // namespace gb
