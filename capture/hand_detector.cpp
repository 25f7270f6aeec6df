#include "capture/hand_detector.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gb {

namespace {

constexpr double kFullHandDensity = 0.003;              // m^2 of sure hand surface around a mode: a whole hand in view
constexpr double kMinConfidence = 0.1;                  // hand modes less sure than this are not detections
constexpr int kLowerEdgeRows = BodyDepth::kHeight / 5;  // lowerEdgeFactor's rows: a fifth of the image
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Whether the performer's body runs from grid pixel (u, v) down to the image's lower edge, within a few pixels either
// side: a limb that leaves the image there. Close to the camera, with the legs cut off by the lower edge, the thighs
// and knees end there like forearms do at the hands, and the forest takes them for hands more often than a real hand
// is there (a hand held that low is usually out of the image).
bool limbLeavesAtLowerEdge(const BodyDepth& body, int u, int v) {
  constexpr int kHalfWidth = 3;  // grid pixels either side (about 4 cm at 1.2 m)
  for (int y = std::max(v, 0); y < BodyDepth::kHeight; ++y) {
    bool row = false;
    for (int x = u - kHalfWidth; x <= u + kHalfWidth && !row; ++x) row = body.at(x, y) < BodyDepth::kBackground;
    if (!row) return false;
  }
  return true;
}

}  // namespace

double lowerEdgeFactor(const BodyDepth& body, const Vec3d& hand) {
  const Eigen::Vector2d px = kinect::cameraToPixel(hand) / 2.0;  // the half-resolution grid
  const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
  return v >= BodyDepth::kHeight - kLowerEdgeRows && limbLeavesAtLowerEdge(body, u, v) ? kLimbAtEdgeFactor : 1.0;
}

Detection detectHands(const kinect::DepthFrame& frame, PerformerSegmenter& segmenter, const DetectionOptions& o) {
  Detection d;
  Segmentation s = segmenter.segment(frame);
  d.floor = s.floor;
  d.why = std::move(s.why);
  d.advice = std::move(s.advice);
  if (s.performer < 0) return d;
  const BodyCandidate& performer = s.candidates[static_cast<size_t>(s.performer)];
  d.bodyDepth = performer.depth;
  d.centre = performer.centre;
  d.body = std::move(s.body);
  for (const float z : d.body.depth) d.performerPixels += z > 0.0f ? 4 : 0;

  const HandForest& forest = o.forest ? *o.forest : HandForest::builtin();
  const auto modes = findHandModes(d.body, forest, o.modes);
  for (int hand = 0; hand < 2; ++hand)
    for (const HandMode& m : modes[static_cast<size_t>(hand)]) {
      DetectedHand h;
      h.position = Vec3d(m.position[0], m.position[1], m.position[2]);
      h.side = hand == 0 ? 1 : -1;
      h.sideConfidence = std::clamp(2.0 * m.share - 1.0, 0.0, 1.0);
      h.confidence = std::min(1.0, m.weight / kFullHandDensity);
      h.confidence *= lowerEdgeFactor(d.body, h.position);
      if (h.confidence >= kMinConfidence) d.hands.push_back(h);
    }
  std::stable_sort(d.hands.begin(), d.hands.end(),
                   [](const DetectedHand& a, const DetectedHand& b) { return a.confidence > b.confidence; });
  return d;
}

Detection detectHands(const kinect::DepthFrame& frame, const DetectionOptions& o) {
  PerformerSegmenter segmenter(o.segmentation);
  return detectHands(frame, segmenter, o);
}

HandTracker::HandTracker(const TrackerOptions& options)
    : options_(options), hold_{HandHold(options.holdTime), HandHold(options.holdTime)} {}

Vec3d HandTracker::predicted(int hand, double time) const {
  // Constant velocity for a short while, then the last position: a held hand is not carried off.
  const double dt = std::min(time - lastSeen_[hand], 0.2);
  return *last_[hand] + dt * velocity_[hand];
}

bool HandTracker::followed(int hand, double time) const {
  return last_[hand] && time - lastSeen_[hand] < options_.followTime;
}

int HandTracker::sideOf(int hand) const {
  // The forest's left hand is the performer's left in an unmirrored image; a mirrored one swaps them.
  const int left = options_.mirrored ? -1 : 1;
  return hand == 0 ? left : -left;
}

double HandTracker::reach(int hand, double time) const {
  return options_.maxHandSpeed * (time - lastSeen_[hand]) + options_.jumpMargin;
}

bool HandTracker::takes(int hand, double time, const DetectedHand& d) const {
  const bool near = followed(hand, time) && (d.position - predicted(hand, time)).norm() <= reach(hand, time);
  return d.confidence >= (near ? options_.followConfidence : options_.newConfidence);
}

void HandTracker::record(int hand, double time, const Vec3d& p) {
  if (last_[hand]) {
    const double dt = time - lastSeen_[hand];
    // A velocity from consecutive frames only; after a gap the hand starts over at rest.
    velocity_[hand] =
        dt > 0.0 && dt < 0.2 ? Vec3d(0.5 * velocity_[hand] + 0.5 * (p - *last_[hand]) / dt) : Vec3d::Zero();
  }
  last_[hand] = p;
  lastSeen_[hand] = time;
}

HandSample HandTracker::update(double time, const Detection& detection) {
  // Each hand's detection: a followed hand's nearest detection of its side within reach of where it was going,
  // when it is sure enough for a followed hand; else the strongest of its side (the list is most confident
  // first), which must be sure enough for a new hand.
  const DetectedHand* best[2] = {nullptr, nullptr};
  for (int h = 0; h < 2; ++h) {
    double nearest = kInfinity;
    const DetectedHand* strongest = nullptr;
    for (const DetectedHand& d : detection.hands) {
      if (d.side != sideOf(h)) continue;
      if (!strongest) best[h] = strongest = &d;
      if (!followed(h, time) || d.confidence < options_.followConfidence) continue;
      const double distance = (d.position - predicted(h, time)).norm();
      if (distance <= reach(h, time) && distance < nearest) nearest = distance, best[h] = &d;
    }
    // The followed detection outweighed by a sure one elsewhere, letGoFrames in a row: let go of it for that one.
    const bool outweighed = strongest && best[h] != strongest && strongest->confidence >= options_.newConfidence &&
                            strongest->confidence >= options_.letGoRatio * best[h]->confidence;
    unsupported_[h] = outweighed ? unsupported_[h] + 1 : 0;
    if (outweighed && unsupported_[h] >= options_.letGoFrames) {
      best[h] = strongest;
      unsupported_[h] = 0;
    }
  }
  std::optional<Vec3d> measured[2];
  double confidence[2] = {1.0, 1.0};
  for (int h = 0; h < 2; ++h) {
    if (!best[h] || !takes(h, time, *best[h])) continue;
    measured[h] = best[h]->position;
    confidence[h] = best[h]->confidence;
  }
  for (int h = 0; h < 2; ++h)
    if (measured[h]) record(h, time, *measured[h]);
  HandSample s;
  s.time = time;
  s.left = hold_[0].update(time, measured[0], confidence[0]);
  s.right = hold_[1].update(time, measured[1], confidence[1]);
  return s;
}

}  // namespace gb
