#pragma once
// How well the hands found in depth match a ground truth, frame by frame: the figures of
// `giantbubble evaluate` and gb_hands_bench (docs/capture.md, "Judged on real depth").
//
// A true hand is found when the hand reported on its own side (the performer's own left or right) is within
// 10 or 15 cm of it in 3D. A reported hand within 15 cm of neither true hand is a false hand. A frame is
// swapped when a reported hand lies within 15 cm of the other side's true hand and not within 15 cm of its
// own. Only hands measured in the frame count (a hand held from an earlier frame is not reported), and only
// frames whose ground truth gives a hand. A true hand not measured but placed (out of the camera's view) is
// not expected, and a hand reported within 15 cm of it is not false.

#include <vector>

#include "capture/depth_recording.h"
#include "capture/hand_finder.h"
#include "capture/hand_source.h"

namespace gb {

struct HandScore {
  long frames = 0;              // frames with at least one true hand
  long truthHands = 0;          // true hands in them
  long within10 = 0;            // true hands found within 10 cm
  long within15 = 0;            //   and within 15 cm
  long reported = 0;            // hands reported in those frames
  long falseHands = 0;          // reported hands near neither true hand
  long swappedFrames = 0;       // frames with a hand reported on the other side
  std::vector<double> errors;   // m: 3D error of each hand found within 15 cm
  double detectionSeconds = 0;  // wall time in detection and tracking

  HandScore& operator+=(const HandScore& other);
  [[nodiscard]] double found10() const { return truthHands ? double(within10) / double(truthHands) : 0.0; }
  [[nodiscard]] double found15() const { return truthHands ? double(within15) / double(truthHands) : 0.0; }
  [[nodiscard]] double falsePerFrame() const { return frames ? double(falseHands) / double(frames) : 0.0; }
  [[nodiscard]] double swappedShare() const { return frames ? double(swappedFrames) / double(frames) : 0.0; }
  [[nodiscard]] double medianError() const;  // m, of the hands found within 15 cm
  [[nodiscard]] double msPerFrame() const { return frames ? 1e3 * detectionSeconds / double(frames) : 0.0; }
};

constexpr double kFoundNear = 0.10;  // m
constexpr double kFoundFar = 0.15;   // m: also the radius within which a reported hand is not false

// Adds one frame: the hands reported against the true ones (same time).
void scoreFrame(const HandSample& reported, const HandSample& truth, HandScore& score);

// Plays a recording through a fresh HandFinder, as fast as it runs, and scores it against its ground truth
// (row i of the truth is frame i). Throws HandSourceError when the recording has no ground truth or its rows
// do not match the frames.
HandScore evaluateRecording(const DepthRecording& recording, const DetectionOptions& detection,
                            const TrackerOptions& tracker);

}  // namespace gb
