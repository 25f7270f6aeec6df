#include "capture/hand_finder.h"

#include "capture/kinect_depth.h"

namespace gb {

std::shared_ptr<const std::vector<Eigen::Vector3f>> bodyPointsOf(const BodyDepth& body) {
  auto points = std::make_shared<std::vector<Eigen::Vector3f>>();
  for (int v = 0; v < body.height; ++v)
    for (int u = 0; u < body.width; ++u)
      if (const float z = body.depth[static_cast<size_t>(v) * static_cast<size_t>(body.width) + static_cast<size_t>(u)];
          z > 0.0f)
        points->push_back(kinect::pixelToCamera(2.0 * (body.left + u), 2.0 * (body.top + v), z).cast<float>());
  return points;
}

HandFinder::HandFinder(const DetectionOptions& detection, const TrackerOptions& tracker)
    : options_(detection), segmenter_(detection.segmentation), tracker_(tracker) {}

HandSample HandFinder::update(const kinect::DepthFrame& frame) {
  detection_ = detectHands(frame, segmenter_, options_);
  HandSample sample = tracker_.update(frame.time, detection_);
  sample.body = detection_.centre;
  if (detection_.performerPixels > 0) sample.bodyPoints = bodyPointsOf(detection_.body);
  return sample;
}

HandSample HandFinder::miss(double time) { return tracker_.update(time, Detection{}); }

}  // namespace gb
