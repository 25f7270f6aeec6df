#include "capture/performer_segmentation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace gb {

using kinect::kHeight;
using kinect::kWidth;

namespace {

// The half-resolution grid everything works on: a body at 2-3 m keeps 5000-15000 points, and a hand tens.
constexpr int kStep = 2;
constexpr int kW = kWidth / kStep, kH = kHeight / kStep, kNodes = kW * kH;
static_assert(kW == BodyDepth::kWidth && kH == BodyDepth::kHeight);

// Depth of one raw disparity step at depth z (m): d/draw of z = 0.1236 tan(raw / 2842.5 + 1.1863).
double depthStep(double z) {
  return (kinect::kTanScale * kinect::kTanScale + z * z) / (kinect::kTanScale * kinect::kTanDivisor);
}

// Two depths of one surface: closer than a few raw steps (at least 7 cm: a hand's side seen at a slant).
double joinTolerance(double z) { return std::max(0.07, 2.5 * depthStep(z)); }

// A depth still the room's: within the noise of a few raw steps (at least 5 cm).
double roomTolerance(double z) { return std::max(0.05, 3.0 * depthStep(z)); }

}  // namespace

// The half-resolution grid of a frame's readings in camera space, and which points hold one.
struct DepthGrid {
  std::vector<Vec3d> point = std::vector<Vec3d>(kNodes, Vec3d::Zero());
  std::vector<uint8_t> valid = std::vector<uint8_t>(kNodes, 0);
};

namespace {

// Each 2 x 2 block's first pixel with a reading inside the band, in camera space.
DepthGrid sampleGrid(const kinect::DepthFrame& frame, const SegmentationOptions& o) {
  const auto& table = kinect::depthTable();
  DepthGrid g;
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u)
      for (int k = 0; k < kStep * kStep; ++k) {
        const int fu = u * kStep + k % kStep, fv = v * kStep + k / kStep;
        const float z = table[frame.raw[static_cast<size_t>(fv) * kWidth + static_cast<size_t>(fu)] & 2047];
        if (z < o.nearLimit || z > o.farLimit) continue;
        g.point[static_cast<size_t>(v * kW + u)] = kinect::pixelToCamera(fu, fv, z);
        g.valid[static_cast<size_t>(v * kW + u)] = 1;
        break;
      }
  return g;
}

// The floor of the grid's points (every other one each way), when one is in view.
std::optional<FloorPlane> gridFloor(const DepthGrid& g, const std::optional<Vec3d>& gravityUp) {
  std::vector<Vec3d> sample;
  for (int v = 0; v < kH; v += 2)
    for (int u = 0; u < kW; u += 2)
      if (g.valid[static_cast<size_t>(v * kW + u)]) sample.push_back(g.point[static_cast<size_t>(v * kW + u)]);
  return findFloor(sample, gravityUp);
}

// The 8 neighbours of node i on the same surface.
template <typename Visit>
void forNeighbours(const DepthGrid& g, int i, Visit visit) {
  const int u = i % kW, v = i / kW;
  const double z = g.point[static_cast<size_t>(i)].z(), tolerance = joinTolerance(z);
  for (int dv = -1; dv <= 1; ++dv) {
    if (v + dv < 0 || v + dv >= kH) continue;
    for (int du = -1; du <= 1; ++du) {
      if ((du == 0 && dv == 0) || u + du < 0 || u + du >= kW) continue;
      const int j = i + dv * kW + du;
      if (g.valid[static_cast<size_t>(j)] && std::abs(g.point[static_cast<size_t>(j)].z() - z) <= tolerance) visit(j);
    }
  }
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2), values.end());
  return values[values.size() / 2];
}

// The connected bodies of the grid's valid points, each at least minBodyArea.
std::vector<BodyCandidate> connectedBodies(const DepthGrid& g, const SegmentationOptions& o) {
  std::vector<BodyCandidate> bodies;
  std::vector<uint8_t> labelled(kNodes, 0);
  std::vector<int> stack;
  for (int seed = 0; seed < kNodes; ++seed) {
    if (!g.valid[static_cast<size_t>(seed)] || labelled[static_cast<size_t>(seed)]) continue;
    BodyCandidate b;
    stack.assign(1, seed);
    labelled[static_cast<size_t>(seed)] = 1;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      b.nodes.push_back(i);
      const double footprint = kStep * g.point[static_cast<size_t>(i)].z() / kinect::kFx;
      b.area += footprint * footprint;
      forNeighbours(g, i, [&](int j) {
        if (!labelled[static_cast<size_t>(j)]) labelled[static_cast<size_t>(j)] = 1, stack.push_back(j);
      });
    }
    if (b.area >= o.minBodyArea) bodies.push_back(std::move(b));
  }
  std::sort(bodies.begin(), bodies.end(),
            [](const BodyCandidate& a, const BodyCandidate& b) { return a.area > b.area; });
  return bodies;
}

// The share of the points within 3 cm of their least-squares plane: near 1 for a wall, a door or a table top,
// well under for a person (a head, arms and legs off the torso's plane).
double flatShare(const DepthGrid& g, const std::vector<int>& nodes) {
  Vec3d mean = Vec3d::Zero();
  for (const int i : nodes) mean += g.point[static_cast<size_t>(i)];
  mean /= static_cast<double>(nodes.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const int i : nodes) {
    const Vec3d d = g.point[static_cast<size_t>(i)] - mean;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Vec3d normal = solver.eigenvectors().col(0);
  int near = 0;
  for (const int i : nodes) near += std::abs(normal.dot(g.point[static_cast<size_t>(i)] - mean)) < 0.03 ? 1 : 0;
  return static_cast<double>(near) / static_cast<double>(nodes.size());
}

// Measures a body: its size along up and across, how much of it moved, how flat it is, where it touches the
// image's edges, how much of it was the performer before.
void measure(const DepthGrid& g, const Vec3d& up, const std::vector<float>& previous, const std::vector<float>& before,
             BodyCandidate& b) {
  std::vector<double> xs, ys, zs;
  double low = std::numeric_limits<double>::infinity(), high = -low, left = low, right = -low;
  int moving = 0, overlap = 0;
  const Vec3d across = Vec3d::UnitX() - up.x() * up;
  for (const int i : b.nodes) {
    const Vec3d& p = g.point[static_cast<size_t>(i)];
    xs.push_back(p.x()), ys.push_back(p.y()), zs.push_back(p.z());
    low = std::min(low, up.dot(p)), high = std::max(high, up.dot(p));
    left = std::min(left, across.dot(p)), right = std::max(right, across.dot(p));
    const float before_z = previous[static_cast<size_t>(i)];
    if (before_z > 0.0f && std::abs(before_z - p.z()) > roomTolerance(p.z())) ++moving;
    // Still the performer's: it was, and is not what their moving away revealed behind them.
    const float performerZ = before[static_cast<size_t>(i)];
    overlap += performerZ > 0.0f && p.z() < performerZ + roomTolerance(p.z()) ? 1 : 0;
    const int u = i % kW, v = i / kW;
    b.cutAbove = b.cutAbove || v <= 1;
    b.cutBelow = b.cutBelow || v >= kH - 2;
    b.cutSide = b.cutSide || u <= 1 || u >= kW - 2;
  }
  const double n = static_cast<double>(b.nodes.size());
  b.centre = Vec3d(median(xs), median(ys), median(zs));
  b.depth = b.centre.z();
  b.height = high - low;
  b.width = right - left;
  b.moving = moving / n;
  b.overlap = overlap / n;
  b.flat = flatShare(g, b.nodes);
}

// Why a body cannot be a person (empty when it can): too large, too wide, too low or too flat. Most of it the
// performer in the frame before: low or flat is forgiven (a performer crouching, or hidden behind furniture).
std::string rejection(const BodyCandidate& b) {
  char text[120];
  if (b.area > 2.5) {
    std::snprintf(text, sizeof text, "%.1f m^2, larger than a person: a wall?", b.area);
    return text;
  }
  if (b.width > 2.6) {
    std::snprintf(text, sizeof text, "%.1f m wide, wider than a person with arms out", b.width);
    return text;
  }
  // A person shows a metre from the head down even when the image cuts their legs off; only a head out of view
  // (a performer close to the camera) excuses less.
  if (b.height < 1.0 && !b.cutAbove && b.overlap < 0.5) {
    std::snprintf(text, sizeof text, "%.2f m tall, lower than a person: furniture?", b.height);
    return text;
  }
  if (b.flat > 0.85 && b.area > 0.25 && b.overlap < 0.5) {
    std::snprintf(text, sizeof text, "flat, %.0f%% within 3 cm of a plane: a wall, a door or a table?", 100 * b.flat);
    return text;
  }
  return {};
}

// The performer is in front: nearer, moving, the one taken before, not cut off by the image's side (someone
// passing by), near the expected distance when one is given; larger bodies are a little more likely.
double performerScore(const BodyCandidate& b, const SegmentationOptions& o) {
  double score = std::sqrt(b.area) / (0.5 + b.depth);
  score *= 1.0 + 2.0 * std::min(1.0, b.moving / 0.05);
  score *= 1.0 + 3.0 * b.overlap;
  if (b.cutSide) score *= 0.3;
  if (o.expectedDistance > 0.0) {
    const double off = (b.depth - o.expectedDistance) / 0.8;
    score *= std::exp(-off * off);
  }
  return score;
}

// Summed-area table of a mask over the grid: how many set nodes lie in any rectangle, in constant time.
class MaskSums {
 public:
  explicit MaskSums(const std::vector<uint8_t>& mask) : sums_(static_cast<size_t>(kW + 1) * (kH + 1), 0) {
    for (int v = 0; v < kH; ++v)
      for (int u = 0; u < kW; ++u)
        sums_[at(u + 1, v + 1)] =
            mask[static_cast<size_t>(v * kW + u)] + sums_[at(u, v + 1)] + sums_[at(u + 1, v)] - sums_[at(u, v)];
  }
  // Set nodes with u in [u0, u1] and v in [v0, v1] (inclusive, inside the grid).
  [[nodiscard]] int count(int u0, int v0, int u1, int v1) const {
    return sums_[at(u1 + 1, v1 + 1)] - sums_[at(u0, v1 + 1)] - sums_[at(u1 + 1, v0)] + sums_[at(u0, v0)];
  }

 private:
  std::vector<int> sums_;
  static size_t at(int u, int v) { return static_cast<size_t>(v) * (kW + 1) + static_cast<size_t>(u); }
};

// Pieces of the performer the grid did not join to the body (a forearm or hand pointing at the camera, seen
// end-on as a few depth steps): a piece nearer than the performer just beside it in the image, within
// kMaxBridge of the performer's nearest point, joins them, in rounds, so that a hand beyond a forearm joins
// too. Returns the performer's nodes with the pieces.
std::vector<int> attachFragments(const DepthGrid& g, const std::vector<std::vector<int>>& pieces,
                                 const std::vector<int>& body) {
  constexpr int kReach = 4;           // half-resolution pixels searched around each piece's point
  constexpr double kMaxBridge = 0.6;  // m: a forearm hidden behind its hand leaves the hand up to an arm in front
  std::vector<int> joined = body;
  std::vector<uint8_t> inBody(kNodes, 0), attached(pieces.size(), 0);
  double bodyDepth = 0.0;
  for (const int i : body) inBody[static_cast<size_t>(i)] = 1, bodyDepth += g.point[static_cast<size_t>(i)].z();
  bodyDepth /= static_cast<double>(body.size());
  for (int round = 0; round < 3; ++round) {
    bool grew = false;
    // Most pieces (the wall, the furniture) have no body point within reach: they are passed over by one look at
    // the table instead of a search of their whole window. Rebuilt when the body grows.
    MaskSums bodyNear(inBody);
    for (size_t f = 0; f < pieces.size(); ++f) {
      if (attached[f]) continue;
      bool near = false;
      for (size_t k = 0; k < pieces[f].size() && !near; ++k) {
        const int i = pieces[f][k];
        const Vec3d& p = g.point[static_cast<size_t>(i)];
        if (p.z() > bodyDepth) continue;  // only nearer pieces: a hand in front of the body, not the wall
        const int u = i % kW, v = i / kW;
        const int u0 = std::max(0, u - kReach), u1 = std::min(kW - 1, u + kReach);
        const int v0 = std::max(0, v - kReach), v1 = std::min(kH - 1, v + kReach);
        if (bodyNear.count(u0, v0, u1, v1) == 0) continue;
        for (int vv = v0; vv <= v1 && !near; ++vv)
          for (int uu = u0; uu <= u1 && !near; ++uu) {
            const int j = vv * kW + uu;
            near = inBody[static_cast<size_t>(j)] && (p - g.point[static_cast<size_t>(j)]).norm() < kMaxBridge;
          }
      }
      if (!near) continue;
      for (const int i : pieces[f]) inBody[static_cast<size_t>(i)] = 1, joined.push_back(i);
      bodyNear = MaskSums(inBody);
      attached[f] = 1;
      grew = true;
    }
    if (!grew) break;
  }
  return joined;
}

// Every grid component (no size limit), for the pieces a performer may have lost.
std::vector<std::vector<int>> smallPieces(const DepthGrid& g, const std::vector<uint8_t>& taken) {
  constexpr size_t kMinPiece = 6;  // nodes: smaller pieces are noise
  std::vector<std::vector<int>> pieces;
  std::vector<uint8_t> labelled = taken;
  std::vector<int> stack;
  for (int seed = 0; seed < kNodes; ++seed) {
    if (!g.valid[static_cast<size_t>(seed)] || labelled[static_cast<size_t>(seed)]) continue;
    std::vector<int> piece;
    stack.assign(1, seed);
    labelled[static_cast<size_t>(seed)] = 1;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      piece.push_back(i);
      forNeighbours(g, i, [&](int j) {
        if (!labelled[static_cast<size_t>(j)]) labelled[static_cast<size_t>(j)] = 1, stack.push_back(j);
      });
    }
    if (piece.size() >= kMinPiece) pieces.push_back(std::move(piece));
  }
  return pieces;
}

std::string describeBody(const BodyCandidate& b) {
  char text[160];
  std::snprintf(text, sizeof text, "the body at %.1f m (%.1f m tall%s, %.1f m wide, %.0f%% moving)", b.depth, b.height,
                b.cutAbove || b.cutBelow ? " in view" : "", b.width, 100 * b.moving);
  return text;
}

// What a performer should change: distance, the edges of the view.
std::string adviceFor(const BodyCandidate& b) {
  if (b.depth > 3.5) return "step closer: beyond 3.5 m hands are few and coarse pixels";
  if (b.cutAbove && b.cutBelow && b.depth < 1.5) return "step back or tilt the camera: only part of you is in view";
  if (b.cutSide) return "step towards the middle of the view";
  return {};
}

}  // namespace

std::optional<FloorPlane> floorOf(const kinect::DepthFrame& frame, const SegmentationOptions& o,
                                  const std::optional<Vec3d>& gravityUp) {
  return gridFloor(sampleGrid(frame, o), gravityUp);
}

PerformerSegmenter::PerformerSegmenter(const SegmentationOptions& options)
    : options_(options),
      room_(kNodes, 0.0f),
      nearer_(kNodes, 0.0f),
      seen_(kNodes, 0),
      nearerFrames_(kNodes, 0),
      reference_(kNodes, 0.0f),
      performer_(kNodes, 0),
      performerDepth_(kNodes, 0.0f),
      sincePerformer_(kNodes, std::numeric_limits<uint16_t>::max()) {}

namespace {

constexpr uint16_t kLearnedAfter = 10;  // frames a depth is seen unchanged before it is the room (1/3 s)
constexpr uint16_t kMovedAfter = 150;   // frames a nearer surface stays before it is the room (5 s)
constexpr int kMotionFrames = 10;       // frames between the depths compared for motion (1/3 s)
constexpr int kStillForRoom = 300;      // frames a performer may stay perfectly still (10 s)
constexpr uint16_t kForgetAfter = 90;   // frames after the performer was last at a point before it is learned

// The candidate a performer is most likely to be (the highest score), or -1 when none may be.
int likeliestPerformer(const std::vector<BodyCandidate>& candidates) {
  int best = -1;
  for (size_t k = 0; k < candidates.size(); ++k)
    if (candidates[k].score > 0.0 && (best < 0 || candidates[k].score > candidates[static_cast<size_t>(best)].score))
      best = static_cast<int>(k);
  return best;
}

// Why nobody was taken, naming the largest body and what ruled it out.
std::string whyNoPerformer(const std::vector<BodyCandidate>& candidates, const SegmentationOptions& o) {
  char text[120];
  std::snprintf(text, sizeof text, "no body in the depth band %.1f-%.1f m", o.nearLimit, o.farLimit);
  std::string why = text;
  if (!candidates.empty()) {
    const BodyCandidate& largest = candidates.front();
    std::snprintf(text, sizeof text, " looks like a person (the largest, at %.1f m: %s)", largest.depth,
                  largest.rejected.c_str());
    why += text;
  }
  return why;
}

}  // namespace

Segmentation PerformerSegmenter::segment(const kinect::DepthFrame& frame) {
  Segmentation s;
  DepthGrid g = sampleGrid(frame, options_);
  const DepthGrid sampled = g;
  const std::optional<Vec3d> gravity = options_.gravityUp ? options_.gravityUp : frame.gravityUp;
  s.floor = gridFloor(g, gravity);
  const Vec3d up = s.floor ? s.floor->up : gravity.value_or(Vec3d::UnitY());
  s.roomLearned = clearFloorAndRoom(g, s.floor);

  s.candidates = connectedBodies(g, options_);
  for (BodyCandidate& b : s.candidates) {
    measure(g, up, reference_, performerDepth_, b);
    b.rejected = rejection(b);
    if (b.rejected.empty()) b.score = performerScore(b, options_);
  }
  s.performer = likeliestPerformer(s.candidates);
  std::fill(performer_.begin(), performer_.end(), uint8_t{0});
  std::fill(performerDepth_.begin(), performerDepth_.end(), 0.0f);
  if (s.performer >= 0) {
    takePerformer(g, s);
  } else {
    s.why = whyNoPerformer(s.candidates, options_);
    s.advice = "step in front of the camera, 1.5-3 m away";
  }
  learnRoom(sampled);
  return s;
}

double PerformerSegmenter::clearFloorAndRoom(DepthGrid& g, const std::optional<FloorPlane>& floor) const {
  int learned = 0;
  for (size_t i = 0; i < static_cast<size_t>(kNodes); ++i) {
    learned += seen_[i] >= kLearnedAfter ? 1 : 0;
    if (!g.valid[i]) continue;
    const double z = g.point[i].z();
    const bool onFloor = floor && floor->heightOf(g.point[i]) < options_.floorClearance;
    const bool room = seen_[i] >= kLearnedAfter && z > room_[i] - roomTolerance(z);
    if (onFloor || room) g.valid[i] = 0;
  }
  return static_cast<double>(learned) / kNodes;
}

void PerformerSegmenter::takePerformer(const DepthGrid& g, Segmentation& s) {
  const BodyCandidate& taken = s.candidates[static_cast<size_t>(s.performer)];
  stillFrames_ = taken.overlap > 0.5 && taken.moving < 0.02 ? stillFrames_ + 1 : 0;
  // The performer split into bodies (arms crossed in front of the chest, a hand before the belly): the other
  // bodies that were mostly the performer before are theirs too.
  std::vector<int> nodes = taken.nodes;
  for (const BodyCandidate& b : s.candidates)
    if (&b != &taken && b.overlap > 0.5 && b.area < 2.5) nodes.insert(nodes.end(), b.nodes.begin(), b.nodes.end());
  std::vector<uint8_t> inBody(kNodes, 0);
  for (const int i : nodes) inBody[static_cast<size_t>(i)] = 1;
  const std::vector<int> body = attachFragments(g, smallPieces(g, inBody), nodes);
  for (const int i : body) {
    performer_[static_cast<size_t>(i)] = 1;
    performerDepth_[static_cast<size_t>(i)] = static_cast<float>(g.point[static_cast<size_t>(i)].z());
    s.body.depth[static_cast<size_t>(i)] = static_cast<float>(g.point[static_cast<size_t>(i)].z());
  }
  s.why = "the performer is " + describeBody(taken);
  if (s.candidates.size() > 1) {
    char more[96];
    std::snprintf(more, sizeof more, ", the most likely of %zu bodies (nearest, moving, taken before)",
                  s.candidates.size());
    s.why += more;
  }
  s.advice = adviceFor(taken);
}

// Learn the room from every reading that is not the performer (nor beside them: their edges), unless the
// performer has not moved for so long that it is part of the room.
// A performer lost for a moment (hidden, or split by a crossing arm) is not learned either: a point is
// learned only kForgetAfter frames after the performer was last at it or beside it.
void PerformerSegmenter::learnRoom(const DepthGrid& sampled) {
  const bool performerIsRoom = stillFrames_ > kStillForRoom;
  std::vector<uint8_t> near(kNodes, 0);
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u)
      if (performer_[static_cast<size_t>(v * kW + u)] && !performerIsRoom)
        for (int dv = -2; dv <= 2; ++dv)
          for (int du = -2; du <= 2; ++du)
            if (u + du >= 0 && u + du < kW && v + dv >= 0 && v + dv < kH)
              near[static_cast<size_t>((v + dv) * kW + u + du)] = 1;
  for (size_t i = 0; i < static_cast<size_t>(kNodes); ++i) {
    sincePerformer_[i] = near[i] ? 0 : static_cast<uint16_t>(std::min<int>(sincePerformer_[i] + 1, 60000));
    near[i] = !performerIsRoom && sincePerformer_[i] < kForgetAfter;
  }
  const bool renewReference = frame_++ % kMotionFrames == 0;
  for (size_t i = 0; i < static_cast<size_t>(kNodes); ++i) {
    if (renewReference) reference_[i] = sampled.valid[i] ? static_cast<float>(sampled.point[i].z()) : 0.0f;
    if (!sampled.valid[i] || near[i]) continue;
    const auto z = static_cast<float>(sampled.point[i].z());
    const auto tolerance = static_cast<float>(roomTolerance(z));
    if (room_[i] == 0.0f || z > room_[i] + tolerance) {  // first seen, or something in front has moved away
      room_[i] = z;
      seen_[i] = 1;
    } else if (z > room_[i] - tolerance) {
      room_[i] += 0.1f * (z - room_[i]);
      seen_[i] = static_cast<uint16_t>(std::min<int>(seen_[i] + 1, 60000));
    } else if (std::abs(z - nearer_[i]) < tolerance && ++nearerFrames_[i] >= kMovedAfter) {
      room_[i] = z;  // a nearer surface that stays: the room has changed (a chair moved)
      seen_[i] = kLearnedAfter;
      nearerFrames_[i] = 0;
    } else if (std::abs(z - nearer_[i]) >= tolerance) {
      nearer_[i] = z;
      nearerFrames_[i] = 1;
    }
  }
}

}  // namespace gb
