#pragma once
// Training the hand forest (hand_forest.h) on depth recordings with a ground truth of the hands, as Shotton et
// al. (CVPR 2011) train theirs: each tree is grown depth first from a random share of the training pixels; at
// each node a few hundred random features, each with a few random thresholds, are tried on a random subset of
// the node's pixels and the one that gains the most information (Shannon entropy of the classes) splits it.
//
// Labels come from the ground truth: a performer's pixel whose surface point lies within handRadius of a true
// hand is that hand, any other performer's pixel is body. Every frame is also learned mirrored, with the sides
// swapped (a performer seen in a mirror is a performer with left and right exchanged), which doubles the data
// and keeps the forest from preferring one side; and from other places (the performer's points moved nearer or
// farther and seen by a camera tilted down, cut off by the image's edges where they leave it), so that the
// forest knows performers at every distance the Kinect measures although the recordings keep them at 3 m.

#include <optional>
#include <random>
#include <vector>

#include "capture/hand_forest.h"
#include "capture/hand_source.h"

namespace gb {

struct ForestTrainingOptions {
  int trees = 3;
  int maxDepth = 20;
  int minLeafPixels = 10;         // a split leaving fewer pixels on one side is not made
  int featuresPerNode = 300;      // random features tried at each node
  int thresholdsPerFeature = 12;  // random thresholds tried for each
  int pixelsPerSplit = 20000;     // at most this many of the node's pixels choose its split
  double pixelsPerTree = 0.6;     // share of the training pixels each tree grows from (bagging)
  double maxOffset = 0.6;         // m: the largest feature offset, each way
  double handRadius = 0.10;       // m: performer's pixels this close to a true hand are that hand
  int bodyPixelsPerFrame = 300;   // body pixels sampled per frame and view
  int handPixelsPerFrame = 200;   // pixels of each hand, at most (a near hand covers thousands)
  int otherViews = 2;             // each frame is also learned from this many other places, chosen at random:
  double nearest = 1.0;           //   the performer moved to a depth between these (m)
  double farthest = 3.8;
  double maxPitch = 20.0;  //   and seen by a camera tilted down by up to this (degrees)
  bool mirrored = true;    // also learn every frame mirrored, sides swapped
  unsigned seed = 1;
};

// One training pixel of one image.
struct TrainingPixel {
  uint32_t image = 0;
  int16_t u = 0, v = 0;  // grid pixel
  float z = 0.0f;        // its depth (m)
  uint8_t label = kBodyPixel;
  float weight = 1.0f;  // how many of the frame's pixels of its class it stands for
};

// A frame as seen (not mirrored) with its true hands, for measuring where hands lie behind the surface found.
struct CalibrationFrame {
  uint32_t image = 0;
  std::optional<Vec3d> hands[2];
};

struct ForestTrainingSet {
  std::vector<BodyDepth> images;  // each cropped to the performer
  std::vector<TrainingPixel> pixels;
  std::vector<CalibrationFrame> calibration;
};

// Adds a frame: the performer's depth and the true hands (camera space; a missing hand labels nothing).
void addTrainingFrame(const BodyDepth& body, const std::optional<Vec3d> (&hands)[2],
                      const ForestTrainingOptions& options, std::mt19937& random, ForestTrainingSet& set);

// Grows the trees, then measures HandForest::surfaceToCentre: the median depth of the true hands behind the
// hands found by findHandModes (without the push back) on the training frames.
HandForest trainHandForest(const ForestTrainingSet& set, const ForestTrainingOptions& options);

// The 3D point of grid pixel (u, v) at depth z (camera space), as the detector places it.
Vec3d gridPoint(int u, int v, double z);

}  // namespace gb
