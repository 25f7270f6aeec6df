#pragma once
// Depth frames in, the performer's two hands out: the one pipeline behind a live Kinect, a fakenect
// recording, `giantbubble evaluate` and the benchmarks. It keeps what one frame cannot know: the room seen
// so far, the performer taken in the frames before, and each hand's identity (HandTracker).

#include "capture/hand_detector.h"

namespace gb {

// The performer's depth points in camera space, one per pixel of the detector's half-resolution grid.
std::shared_ptr<const std::vector<Eigen::Vector3f>> bodyPointsOf(const BodyDepth& body);

class HandFinder {
 public:
  explicit HandFinder(const DetectionOptions& detection = {}, const TrackerOptions& tracker = {});
  // The hands of the next frame (frame.time increasing).
  HandSample update(const kinect::DepthFrame& frame);
  // No frame came by `time`: both hands held.
  HandSample miss(double time);
  // What the newest frame showed: the performer, the hands found and why.
  [[nodiscard]] const Detection& detection() const { return detection_; }
  [[nodiscard]] const DetectionOptions& options() const { return options_; }

 private:
  DetectionOptions options_;
  PerformerSegmenter segmenter_;
  HandTracker tracker_;
  Detection detection_;
};

}  // namespace gb
