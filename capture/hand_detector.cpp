#include "hand_detector.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace gb {

using kinect::kHeight;
using kinect::kPixels;
using kinect::kWidth;

namespace {

constexpr int kCell = 4;  // extremities are searched on a grid of kCell x kCell pixel cells
constexpr int kCellsX = kWidth / kCell, kCellsY = kHeight / kCell;
constexpr int kMinHandPixels = 40;  // fewer points around an extremity: a speck of noise, not a hand

// Depth in metres of every pixel inside the band, 0 elsewhere.
std::vector<float> bandDepths(const kinect::DepthFrame& frame, const DetectionOptions& o) {
  const auto& table = kinect::depthTable();
  std::vector<float> z(kPixels, 0.0f);
  for (int i = 0; i < kPixels; ++i) {
    const float d = table[frame.raw[i] & 2047];
    if (d >= o.nearLimit && d <= o.farLimit) z[i] = d;
  }
  return z;
}

// Labels the connected regions (4-neighbours, depth steps under depthJump) and returns the mask of the
// nearest one (by mean depth) with at least minPerformerPixels pixels; empty when there is none.
std::vector<uint8_t> performerMask(const std::vector<float>& z, const DetectionOptions& o, int& pixels) {
  std::vector<int> label(kPixels, -1), stack;
  int best = -1;
  double bestMean = std::numeric_limits<double>::infinity();
  int next = 0;
  for (int seed = 0; seed < kPixels; ++seed) {
    if (z[seed] == 0.0f || label[seed] >= 0) continue;
    const int id = next++;
    int count = 0;
    double sum = 0.0;
    label[seed] = id;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      ++count;
      sum += z[i];
      const int u = i % kWidth, v = i / kWidth;
      const int neighbours[4] = {u > 0 ? i - 1 : -1, u + 1 < kWidth ? i + 1 : -1, v > 0 ? i - kWidth : -1,
                                 v + 1 < kHeight ? i + kWidth : -1};
      for (const int j : neighbours) {
        if (j < 0 || z[j] == 0.0f || label[j] >= 0 || std::abs(z[j] - z[i]) > o.depthJump) continue;
        label[j] = id;
        stack.push_back(j);
      }
    }
    if (count >= o.minPerformerPixels && sum / count < bestMean) {
      bestMean = sum / count;
      best = id;
      pixels = count;
    }
  }
  std::vector<uint8_t> mask;
  if (best < 0) return mask;
  mask.resize(kPixels);
  for (int i = 0; i < kPixels; ++i) mask[i] = label[i] == best;
  return mask;
}

struct Extremity {
  int pixel;
  float z;
};

// Cells whose nearest in-front point is the nearest within extremityRadius: the performer's extremities.
std::vector<Extremity> extremities(const std::vector<float>& z, const std::vector<uint8_t>& mask, float inFront,
                                   const DetectionOptions& o) {
  std::vector<Extremity> cells(kCellsX * kCellsY, Extremity{-1, std::numeric_limits<float>::infinity()});
  for (int i = 0; i < kPixels; ++i) {
    if (!mask[i] || z[i] >= inFront) continue;
    Extremity& c = cells[(i / kWidth / kCell) * kCellsX + (i % kWidth) / kCell];
    if (z[i] < c.z) c = {i, z[i]};
  }
  std::vector<Extremity> found;
  for (int cy = 0; cy < kCellsY; ++cy) {
    for (int cx = 0; cx < kCellsX; ++cx) {
      const Extremity& c = cells[cy * kCellsX + cx];
      if (c.pixel < 0) continue;
      const int r = static_cast<int>(std::ceil(o.extremityRadius * kinect::kFx / c.z / kCell));
      bool nearest = true;
      for (int y = std::max(0, cy - r); nearest && y <= std::min(kCellsY - 1, cy + r); ++y) {
        for (int x = std::max(0, cx - r); x <= std::min(kCellsX - 1, cx + r); ++x) {
          const Extremity& other = cells[y * kCellsX + x];
          if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > r * r || other.pixel < 0) continue;
          // Ties go to the earlier cell, so a flat front yields one extremity, not a plateau of them.
          if (other.z < c.z || (other.z == c.z && y * kCellsX + x < cy * kCellsX + cx)) {
            nearest = false;
            break;
          }
        }
      }
      if (nearest) found.push_back(c);
    }
  }
  std::sort(found.begin(), found.end(), [](const Extremity& a, const Extremity& b) { return a.z < b.z; });
  return found;
}

Vec3d pointAt(int pixel, float z) { return kinect::pixelToCamera(pixel % kWidth, pixel / kWidth, z); }

// Centroid of the performer's points within handRadius of the extremity, pushed back to the hand's centre.
std::optional<DetectedHand> handAround(const std::vector<float>& z, const std::vector<uint8_t>& mask,
                                       const Extremity& tip, const DetectionOptions& o) {
  const Vec3d tipPoint = pointAt(tip.pixel, tip.z);
  const int r = static_cast<int>(std::ceil(o.handRadius * kinect::kFx / tip.z)) + 1;
  const int tu = tip.pixel % kWidth, tv = tip.pixel / kWidth;
  Vec3d sum = Vec3d::Zero();
  int count = 0;
  for (int v = std::max(0, tv - r); v <= std::min(kHeight - 1, tv + r); ++v) {
    for (int u = std::max(0, tu - r); u <= std::min(kWidth - 1, tu + r); ++u) {
      const int i = v * kWidth + u;
      if (!mask[i]) continue;
      const Vec3d p = pointAt(i, z[i]);
      if ((p - tipPoint).norm() > o.handRadius) continue;
      sum += p;
      ++count;
    }
  }
  if (count < kMinHandPixels) return std::nullopt;
  DetectedHand hand{sum / count, count};
  hand.position.z() += o.surfaceToCentre;
  return hand;
}

}  // namespace

Detection detectHands(const kinect::DepthFrame& frame, const DetectionOptions& o) {
  Detection d;
  const std::vector<float> z = bandDepths(frame, o);
  const std::vector<uint8_t> mask = performerMask(z, o, d.performerPixels);
  if (mask.empty()) {
    d.performerPixels = 0;
    return d;
  }
  std::vector<float> depths;
  depths.reserve(static_cast<size_t>(d.performerPixels));
  double sumX = 0.0;
  for (int i = 0; i < kPixels; ++i) {
    if (!mask[i]) continue;
    depths.push_back(z[i]);
    sumX += pointAt(i, z[i]).x();
  }
  std::nth_element(depths.begin(), depths.begin() + static_cast<long>(depths.size() / 2), depths.end());
  d.bodyDepth = depths[depths.size() / 2];
  d.bodyCentreX = sumX / static_cast<double>(depths.size());

  std::vector<Vec3d> tips;
  for (const Extremity& tip : extremities(z, mask, static_cast<float>(d.bodyDepth) - o.minExtension, o)) {
    if (d.hands.size() == 2) break;
    const Vec3d p = pointAt(tip.pixel, tip.z);
    if (std::any_of(tips.begin(), tips.end(), [&](const Vec3d& q) { return (q - p).norm() < o.minHandSeparation; }))
      continue;
    if (auto hand = handAround(z, mask, tip, o)) {
      d.hands.push_back(*hand);
      tips.push_back(p);
    }
  }
  return d;
}

HandTracker::HandTracker(const TrackerOptions& options)
    : options_(options), hold_{HandHold(options.holdTime), HandHold(options.holdTime)} {}

bool HandTracker::withinReach(int hand, double time, const Vec3d& p) const {
  const double reach = options_.maxHandSpeed * (time - lastSeen_[hand]) + options_.jumpMargin;
  return (p - *last_[hand]).norm() <= reach;
}

bool HandTracker::onLeftSide(const Vec3d& p, double referenceX) const {
  // Facing the camera, the performer's left hand is on the camera's right (x > reference) unless mirrored.
  return options_.mirrored ? p.x() < referenceX : p.x() > referenceX;
}

HandSample HandTracker::update(double time, const Detection& detection) {
  const auto& found = detection.hands;
  const int n = static_cast<int>(found.size());
  // Every way of giving the detections to the hands: target[i] is 0 (left), 1 (right) or -1 (neither).
  int bestTarget[2] = {-1, -1}, bestCount = 0;
  double bestCost = std::numeric_limits<double>::infinity();
  for (int a = -1; a < 2; ++a) {
    for (int b = -1; b < 2; ++b) {
      const int target[2] = {a, n > 1 ? b : -1};
      if (n < 1 && a >= 0) continue;
      if (n < 2 && b >= 0) continue;
      if (target[0] >= 0 && target[0] == target[1]) continue;
      bool valid = true;
      int count = 0;
      double cost = 0.0;
      for (int i = 0; i < n && valid; ++i) {
        const int h = target[i];
        if (h < 0) continue;
        ++count;
        const Vec3d& p = found[i].position;
        if (last_[h]) {
          valid = withinReach(h, time, p);
          cost += (p - *last_[h]).norm();
        } else {
          // A hand seen for the first time takes its side: relative to the other hand when that one is
          // known (seen before or taken in this frame), else relative to the body's centre.
          const int other = 1 - h;
          std::optional<double> referenceX;
          for (int j = 0; j < n; ++j)
            if (target[j] == other) referenceX = found[j].position.x();
          if (!referenceX && last_[other]) referenceX = last_[other]->x();
          const bool left = onLeftSide(p, referenceX.value_or(detection.bodyCentreX));
          valid = left == (h == 0);
        }
      }
      if (!valid) continue;
      if (count > bestCount || (count == bestCount && cost < bestCost)) {
        bestCount = count;
        bestCost = cost;
        bestTarget[0] = target[0];
        bestTarget[1] = target[1];
      }
    }
  }
  std::optional<Vec3d> measured[2];
  for (int i = 0; i < n; ++i) {
    if (bestTarget[i] < 0) continue;
    measured[bestTarget[i]] = found[i].position;
    last_[bestTarget[i]] = found[i].position;
    lastSeen_[bestTarget[i]] = time;
  }
  HandSample s;
  s.time = time;
  s.left = hold_[0].update(time, measured[0]);
  s.right = hold_[1].update(time, measured[1]);
  return s;
}

}  // namespace gb
