#include "capture/hand_evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace gb {

namespace {

// A hand of the sample as scored: measured in it (reported) or given by the ground truth.
std::optional<Vec3d> measuredHand(const HandSample& s, int hand) {
  const HandObservation& o = s.hand(hand == 0 ? Hand::Left : Hand::Right);
  if (!o.measured || !o.seen()) return std::nullopt;
  return o.position;
}

bool near(const std::optional<Vec3d>& a, const std::optional<Vec3d>& b, double radius) {
  return a && b && (*a - *b).norm() <= radius;
}

// Where a true hand is, measured or not (a hand out of the camera's view is not expected to be found, but a hand
// reported near it is not false either).
std::optional<Vec3d> whereIs(const HandSample& s, int hand) {
  const HandObservation& o = s.hand(hand == 0 ? Hand::Left : Hand::Right);
  if (!o.seen()) return std::nullopt;
  return o.position;
}

}  // namespace

HandScore& HandScore::operator+=(const HandScore& o) {
  frames += o.frames;
  truthHands += o.truthHands;
  within10 += o.within10;
  within15 += o.within15;
  reported += o.reported;
  falseHands += o.falseHands;
  swappedFrames += o.swappedFrames;
  errors.insert(errors.end(), o.errors.begin(), o.errors.end());
  detectionSeconds += o.detectionSeconds;
  return *this;
}

double HandScore::medianError() const {
  if (errors.empty()) return 0.0;
  std::vector<double> sorted = errors;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
  return sorted[sorted.size() / 2];
}

void scoreFrame(const HandSample& reported, const HandSample& truth, HandScore& score) {
  const std::optional<Vec3d> found[2] = {measuredHand(reported, 0), measuredHand(reported, 1)};
  const std::optional<Vec3d> real[2] = {measuredHand(truth, 0), measuredHand(truth, 1)};
  const std::optional<Vec3d> known[2] = {whereIs(truth, 0), whereIs(truth, 1)};
  if (!real[0] && !real[1]) return;
  ++score.frames;
  bool swapped = false;
  for (int h = 0; h < 2; ++h) {
    if (real[h]) {
      ++score.truthHands;
      if (near(found[h], real[h], kFoundNear)) ++score.within10;
      if (near(found[h], real[h], kFoundFar)) {
        ++score.within15;
        score.errors.push_back((*found[h] - *real[h]).norm());
      }
    }
    if (!found[h]) continue;
    ++score.reported;
    const bool own = near(found[h], known[h], kFoundFar), other = near(found[h], known[1 - h], kFoundFar);
    if (!own && !other) ++score.falseHands;
    if (!own && near(found[h], real[1 - h], kFoundFar)) swapped = true;
  }
  if (swapped) ++score.swappedFrames;
}

HandScore evaluateRecording(const DepthRecording& recording, const DetectionOptions& detection,
                            const TrackerOptions& tracker) {
  const std::string where = "recording " + recording.name;
  if (recording.truth.empty()) throw HandSourceError(where + ": no ground truth (hands.csv)");
  if (recording.truth.size() != recording.frames.size())
    throw HandSourceError(where + ": " + std::to_string(recording.truth.size()) + " rows of ground truth for " +
                          std::to_string(recording.frames.size()) + " depth frames (one row per frame)");
  HandFinder finder(detection, tracker);
  HandScore score;
  for (size_t i = 0; i < recording.frames.size(); ++i) {
    const auto start = std::chrono::steady_clock::now();
    const HandSample found = finder.update(recording.frames[i]);
    score.detectionSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    scoreFrame(found, recording.truth[i], score);
  }
  return score;
}

}  // namespace gb
