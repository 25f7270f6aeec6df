#include "hand_finder.h"

namespace gb {

HandFinder::HandFinder(const DetectionOptions& detection, const TrackerOptions& tracker)
    : options_(detection), segmenter_(detection.segmentation), tracker_(tracker) {}

HandSample HandFinder::update(const kinect::DepthFrame& frame) {
  detection_ = detectHands(frame, segmenter_, options_);
  HandSample sample = tracker_.update(frame.time, detection_);
  sample.body = detection_.centre;
  return sample;
}

HandSample HandFinder::miss(double time) { return tracker_.update(time, Detection{}); }

}  // namespace gb
