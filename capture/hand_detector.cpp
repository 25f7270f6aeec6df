#include "hand_detector.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <unordered_map>

namespace gb {

using kinect::kHeight;
using kinect::kWidth;

namespace {

// The half-resolution grid everything below works on: a Kinect body at 2-3 m keeps 5000-15000 points, few
// enough for several shortest-path passes per frame, and a hand still keeps tens of them.
constexpr int kStep = 2;
constexpr int kW = kWidth / kStep, kH = kHeight / kStep, kNodes = kW * kH;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kMinExtremumGain = 0.15;       // m: an accumulative extremum nearer than this to the others is noise
constexpr double kArmLength = 0.6;              // m from the shoulder to the hand's tip: where the arm leaves the torso
constexpr double kMinConfidence = 0.1;          // hands less sure than this are not reported
constexpr double kFootHeight = 0.4;             // m over the floor: extrema below are feet (a hanging hand is ~0.8 m)
constexpr double kHeadLateral = 0.15;           // m: the head's extremum is within this of the torso's middle
constexpr double kLowestArmRoot = -0.1;         // m over the centre: an arm leaves the torso above this, a leg below
constexpr double kHeadAbove[2] = {0.35, 0.88};  // m over the centre (at the body's median height): the head's top

struct Grid {
  std::vector<Vec3d> point = std::vector<Vec3d>(kNodes, Vec3d::Zero());
  std::vector<uint8_t> valid = std::vector<uint8_t>(kNodes, 0);
  // Edges beyond the grid's neighbours: a forearm pointing at the camera is foreshortened into depth steps
  // the grid does not join, and is bridged to the body where it comes closest (attachFragments). Like the
  // grid's own edges, a bridge is as long as the 3D distance between its ends.
  std::unordered_map<int, std::vector<int>> bridges;
  std::vector<uint8_t> bridged = std::vector<uint8_t>(kNodes, 0);  // has bridges: the map is looked up only then
};

// Each 2 x 2 block's first pixel with a reading inside the band, in camera space.
Grid sampleGrid(const kinect::DepthFrame& frame, const DetectionOptions& o) {
  const auto& table = kinect::depthTable();
  Grid g;
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u)
      for (int k = 0; k < kStep * kStep; ++k) {
        const int fu = u * kStep + k % kStep, fv = v * kStep + k / kStep;
        const float z = table[frame.raw[static_cast<size_t>(fv) * kWidth + fu] & 2047];
        if (z < o.nearLimit || z > o.farLimit) continue;
        g.point[v * kW + u] = kinect::pixelToCamera(fu, fv, z);
        g.valid[v * kW + u] = 1;
        break;
      }
  return g;
}

// The floor of the grid's points (every other one each way), when one is in view.
std::optional<FloorPlane> gridFloor(const Grid& g, const std::optional<Vec3d>& gravityUp) {
  std::vector<Vec3d> sample;
  for (int v = 0; v < kH; v += 2)
    for (int u = 0; u < kW; u += 2)
      if (g.valid[v * kW + u]) sample.push_back(g.point[v * kW + u]);
  return findFloor(sample, gravityUp);
}

// Drops the floor (and anything under it): returns the plane when one is in view.
std::optional<FloorPlane> removeFloor(Grid& g, const std::optional<Vec3d>& gravityUp, const DetectionOptions& o) {
  std::optional<FloorPlane> floor = gridFloor(g, gravityUp);
  if (!floor) return floor;
  for (int i = 0; i < kNodes; ++i)
    if (g.valid[i] && floor->heightOf(g.point[i]) < o.floorClearance) g.valid[i] = 0;
  return floor;
}

// The 8 neighbours of node i joined to it (valid, depth step under depthJump), and its bridges. An edge's
// length is the 3D distance between its ends; the callers that need it compute it.
template <typename Visit>
void forNeighbours(const Grid& g, int i, const DetectionOptions& o, Visit visit) {
  const int u = i % kW, v = i / kW;
  const double z = g.point[i].z();
  for (int dv = -1; dv <= 1; ++dv) {
    if (v + dv < 0 || v + dv >= kH) continue;
    for (int du = -1; du <= 1; ++du) {
      if ((du == 0 && dv == 0) || u + du < 0 || u + du >= kW) continue;
      const int j = i + dv * kW + du;
      if (g.valid[j] && std::abs(g.point[j].z() - z) <= o.depthJump) visit(j);
    }
  }
  if (g.bridged[i])
    for (const int j : g.bridges.at(i))
      if (g.valid[j]) visit(j);
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2), values.end());
  return values[values.size() / 2];
}

struct Bodies {
  std::vector<int> label = std::vector<int>(kNodes, -1);  // component of each valid node
  std::vector<std::vector<int>> members;                  // nodes of each component
  int performer = -1;
};

// The connected bodies of the grid; the performer is the largest (in square metres) of a person's height and
// width, the nearer to the expected distance the better.
Bodies connectedBodies(const Grid& g, const Vec3d& up, const DetectionOptions& o) {
  Bodies b;
  std::vector<int> stack;
  double bestScore = 0.0;
  for (int seed = 0; seed < kNodes; ++seed) {
    if (!g.valid[seed] || b.label[seed] >= 0) continue;
    const int id = static_cast<int>(b.members.size());
    std::vector<int>& members = b.members.emplace_back();
    stack.assign(1, seed);
    b.label[seed] = id;
    double area = 0.0, low = kInfinity, high = -kInfinity, left = kInfinity, right = -kInfinity, depth = 0.0;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      members.push_back(i);
      const Vec3d& p = g.point[i];
      const double footprint = kStep * p.z() / kinect::kFx;
      area += footprint * footprint;
      depth += p.z();
      const double height = up.dot(p);
      low = std::min(low, height), high = std::max(high, height);
      left = std::min(left, p.x()), right = std::max(right, p.x());
      forNeighbours(g, i, o, [&](int j) {
        if (b.label[j] < 0) b.label[j] = id, stack.push_back(j);
      });
    }
    if (static_cast<int>(members.size()) * kStep * kStep < o.minPerformerPixels) continue;
    // A person: at least 0.9 m tall in view (legs may be cut off), at most 2.4 m across (arms out), and not a
    // wall's many square metres.
    if (high - low < 0.9 || right - left > 2.4 || area > 2.5) continue;
    depth /= static_cast<double>(members.size());
    const double off = o.expectedDistance > 0.0 ? (depth - o.expectedDistance) / 0.8 : 0.0;
    const double score = area * std::exp(-off * off);
    if (score > bestScore) bestScore = score, b.performer = id;
  }
  return b;
}

// Pieces of the performer the grid did not join to the body (a forearm or hand pointing at the camera, seen
// end-on as a few depth steps): a body nearer than the performer just beside it in the image is bridged to
// the performer's nearest point within kMaxBridge, in rounds, so that a hand beyond a forearm joins too.
// Summed-area table of a mask over the grid: how many set nodes lie in any rectangle, in constant time.
class MaskSums {
 public:
  explicit MaskSums(const std::vector<uint8_t>& mask) : sums_(static_cast<size_t>(kW + 1) * (kH + 1), 0) {
    for (int v = 0; v < kH; ++v)
      for (int u = 0; u < kW; ++u)
        sums_[at(u + 1, v + 1)] = mask[v * kW + u] + sums_[at(u, v + 1)] + sums_[at(u + 1, v)] - sums_[at(u, v)];
  }
  // Set nodes with u in [u0, u1] and v in [v0, v1] (inclusive, inside the grid).
  [[nodiscard]] int count(int u0, int v0, int u1, int v1) const {
    return sums_[at(u1 + 1, v1 + 1)] - sums_[at(u0, v1 + 1)] - sums_[at(u1 + 1, v0)] + sums_[at(u0, v0)];
  }

 private:
  std::vector<int> sums_;
  static size_t at(int u, int v) { return static_cast<size_t>(v) * (kW + 1) + u; }
};

std::vector<int> attachFragments(Grid& g, const Bodies& b) {
  constexpr int kReach = 4;           // half-resolution pixels searched around each fragment point
  constexpr double kMaxBridge = 0.6;  // m: a forearm hidden behind its hand leaves the hand up to an arm in front
  constexpr int kMinFragment = 6;     // nodes: smaller pieces are noise
  std::vector<int> body = b.members[b.performer];
  std::vector<uint8_t> inBody(kNodes, 0), attached(b.members.size(), 0);
  for (const int i : body) inBody[i] = 1;
  attached[b.performer] = 1;
  for (int round = 0; round < 3; ++round) {
    bool grew = false;
    // Most fragment points (the wall, the furniture) have no body point within reach: they are passed over
    // by one look at the table instead of a search of their whole window. Rebuilt when the body grows.
    MaskSums bodyNear(inBody);
    for (size_t f = 0; f < b.members.size(); ++f) {
      if (attached[f] || static_cast<int>(b.members[f].size()) < kMinFragment) continue;
      int from = -1, to = -1;
      double shortest = kMaxBridge;
      for (const int i : b.members[f]) {
        const int u = i % kW, v = i / kW;
        const int u0 = std::max(0, u - kReach), u1 = std::min(kW - 1, u + kReach);
        const int v0 = std::max(0, v - kReach), v1 = std::min(kH - 1, v + kReach);
        if (bodyNear.count(u0, v0, u1, v1) == 0) continue;
        for (int y = v0; y <= v1; ++y)
          for (int x = u0; x <= u1; ++x) {
            const int j = y * kW + x;
            // The fragment must be in front of the body there: it occludes it, it is not a wall behind.
            if (!inBody[j] || g.point[i].z() > g.point[j].z() + 0.05) continue;
            const double d = (g.point[i] - g.point[j]).norm();
            if (d < shortest) shortest = d, from = i, to = j;
          }
      }
      if (from < 0) continue;
      g.bridges[from].push_back(to);
      g.bridges[to].push_back(from);
      g.bridged[from] = g.bridged[to] = 1;
      for (const int i : b.members[f]) inBody[i] = 1, body.push_back(i);
      bodyNear = MaskSums(inBody);
      attached[f] = 1;
      grew = true;
    }
    if (!grew) break;
  }
  return body;
}

// Shortest paths over the body's surface graph from `source`, lowering dist where they are shorter; pred (when
// given) records the tree.
void geodesicFrom(const Grid& g, int source, const DetectionOptions& o, std::vector<double>& dist,
                  std::vector<int>* pred) {
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  dist[source] = 0.0;
  if (pred) (*pred)[source] = -1;
  queue.push({0.0, source});
  while (!queue.empty()) {
    const double d = queue.top().first;  // not a structured binding: clang 14 (the sanitizer build) cannot
    const int i = queue.top().second;    // capture one in the lambda below
    queue.pop();
    if (d > dist[i]) continue;
    forNeighbours(g, i, o, [&](int j) {
      const double w = (g.point[j] - g.point[i]).norm();
      if (d + w < dist[j]) {
        dist[j] = d + w;
        if (pred) (*pred)[j] = i;
        queue.push({dist[j], j});
      }
    });
  }
}

// The torso's centre: the body point nearest the medians of the body's middle height band.
int torsoCentre(const Grid& g, const std::vector<int>& body, const Vec3d& up) {
  std::vector<double> heights;
  for (const int i : body) heights.push_back(up.dot(g.point[i]));
  const double mid = median(heights);
  std::vector<double> xs, zs;
  for (const int i : body)
    if (std::abs(up.dot(g.point[i]) - mid) < 0.15) xs.push_back(g.point[i].x()), zs.push_back(g.point[i].z());
  const double mx = median(xs), mz = median(zs);
  int best = body.front();
  double bestDistance = kInfinity;
  for (const int i : body) {
    const Vec3d& p = g.point[i];
    const double dh = up.dot(p) - mid, d = (p.x() - mx) * (p.x() - mx) + dh * dh + (p.z() - mz) * (p.z() - mz);
    if (d < bestDistance) bestDistance = d, best = i;
  }
  return best;
}

// The hand around a tip: the connected surface within handRadius of it, its centroid pushed back along the
// ray to the hand's centre.
DetectedHand handAt(const Grid& g, int tip, const DetectionOptions& o) {
  std::vector<int> stack{tip}, seen{tip};
  std::vector<uint8_t> visited(kNodes, 0);
  visited[tip] = 1;
  Vec3d sum = Vec3d::Zero();
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    sum += g.point[i];
    forNeighbours(g, i, o, [&](int j) {
      if (visited[j] || (g.point[j] - g.point[tip]).norm() > o.handRadius) return;
      visited[j] = 1;
      stack.push_back(j);
      seen.push_back(j);
    });
  }
  DetectedHand hand;
  hand.pixels = static_cast<int>(seen.size());
  hand.position = sum / hand.pixels;
  hand.position += o.surfaceToCentre * hand.position.normalized();
  return hand;
}

struct ArmRoot {
  int node = -1;         // where the tip's limb leaves the torso
  bool bridged = false;  // the path there crosses a bridge (attachFragments), not the arm's own surface
};

// The point an arm's length back along the tip's shortest path to the centre.
ArmRoot armRoot(int tip, const std::vector<double>& fromCentre, const std::vector<int>& pred) {
  const double shoulder = std::max(0.2, fromCentre[tip] - kArmLength);
  ArmRoot root{tip, false};
  while (pred[root.node] >= 0 && fromCentre[root.node] > shoulder) {
    const int next = pred[root.node];
    root.bridged = root.bridged || std::abs(next % kW - root.node % kW) > 1 || std::abs(next / kW - root.node / kW) > 1;
    root.node = next;
  }
  return root;
}

// Which side of the torso the arm leaves by: its root against the torso's centre. Sure when the root is well
// to one side and a whole arm's length back from the tip along the arm's own surface (a hand bridged to the
// chest, or a shorter path, ends wherever the bridge landed and says nothing).
void armSide(const ArmRoot& root, const Vec3d& rootPoint, double centreX, DetectedHand& hand) {
  const double dx = rootPoint.x() - centreX;
  hand.side = dx > 0.0 ? 1 : -1;
  hand.sideConfidence =
      root.bridged ? 0.0 : std::min(1.0, std::abs(dx) / 0.1) * std::clamp((hand.geodesic - kArmLength) / 0.2, 0.0, 1.0);
}

// A hand is in front of the body, or out beside it, above the head or level with it, or hanging beside the
// hips; an extremum at the body's depth within its outline is a shoulder or an elbow bared by arms crossed in
// front of the chest.
bool clearOfTorso(const Vec3d& tip, const Vec3d& centre, const Vec3d& up, double bodyDepth,
                  const std::optional<Vec3d>& head) {
  constexpr double kInFront = 0.12, kBeside = 0.3, kOverhead = 0.75, kHanging = 0.2, kHeadLevel = 0.15;  // m
  if (tip.z() < bodyDepth - kInFront) return true;
  if (head && up.dot(tip - *head) > -kHeadLevel) return true;
  const double beside = std::abs(tip.x() - centre.x()), above = up.dot(tip - centre);
  return beside > kBeside || above > kOverhead || (above < -0.05 && beside > kHanging);
}

// Two candidates on the same arm: one hand found twice (closer than kSameHand), or the elbow and the hand of an
// arm reaching forward (same side of the torso, closer than a forearm and hand, one well in front of the
// other). The hand is the one in front (nearer the camera), else the more confident.
void dropElbows(std::vector<DetectedHand>& candidates) {
  constexpr double kSameArm = 0.45, kInFront = 0.1, kSameHand = 0.1;  // m
  std::vector<uint8_t> dropped(candidates.size(), 0);
  for (size_t a = 0; a < candidates.size(); ++a)
    for (size_t b = a + 1; b < candidates.size(); ++b) {
      const DetectedHand &p = candidates[a], &q = candidates[b];
      const double apart = (p.position - q.position).norm(), dz = p.position.z() - q.position.z();
      const bool sameHand = apart < kSameHand;
      const bool elbowBehind = apart < kSameArm && p.side == q.side && std::abs(dz) > kInFront;
      if (!sameHand && !elbowBehind) continue;
      const bool dropP = dz > kInFront || (std::abs(dz) <= kInFront && p.confidence < q.confidence);
      dropped[dropP ? a : b] = 1;
    }
  size_t kept = 0;
  for (size_t i = 0; i < candidates.size(); ++i)
    if (!dropped[i]) candidates[kept++] = candidates[i];
  candidates.resize(kept);
}

}  // namespace

std::optional<FloorPlane> floorOf(const kinect::DepthFrame& frame, const DetectionOptions& o,
                                  const std::optional<Vec3d>& gravityUp) {
  return gridFloor(sampleGrid(frame, o), gravityUp);
}

Detection detectHands(const kinect::DepthFrame& frame, const DetectionOptions& o) {
  Detection d;
  Grid g = sampleGrid(frame, o);
  const std::optional<Vec3d> gravity = o.gravityUp ? o.gravityUp : frame.gravityUp;
  d.floor = removeFloor(g, gravity, o);
  const Vec3d up = d.floor ? d.floor->up : gravity.value_or(Vec3d::UnitY());
  const Bodies bodies = connectedBodies(g, up, o);
  if (bodies.performer < 0) return d;
  const std::vector<int> body = attachFragments(g, bodies);
  d.performerPixels = static_cast<int>(body.size()) * kStep * kStep;
  std::vector<double> depths;
  for (const int i : body) depths.push_back(g.point[i].z());
  d.bodyDepth = median(depths);

  // Only the performer's nodes take part in the paths.
  Grid& bodyGrid = g;
  std::fill(bodyGrid.valid.begin(), bodyGrid.valid.end(), uint8_t{0});
  for (const int i : body) bodyGrid.valid[i] = 1;
  const int centre = torsoCentre(bodyGrid, body, up);
  const Vec3d c = bodyGrid.point[centre];
  d.centre = c;
  d.bodyCentreX = c.x();
  std::vector<double> fromCentre(kNodes, kInfinity);
  std::vector<int> pred(kNodes, -1);
  geodesicFrom(bodyGrid, centre, o, fromCentre, &pred);

  // Accumulative geodesic extrema: each one the farthest point from the centre and all extrema before it.
  std::vector<double> accumulated = fromCentre;
  std::vector<int> tips;
  std::vector<double> gains;  // how far each extremum stood from the centre and the extrema before it
  for (int k = 0; k < o.extrema; ++k) {
    int far = -1;
    for (const int i : body)
      if (std::isfinite(accumulated[i]) && (far < 0 || accumulated[i] > accumulated[far])) far = i;
    if (far < 0 || accumulated[far] < kMinExtremumGain) break;
    tips.push_back(far);
    gains.push_back(accumulated[far]);
    d.extrema.push_back(bodyGrid.point[far]);
    geodesicFrom(bodyGrid, far, o, accumulated, nullptr);
  }

  // Feet are low; the head is the most central extremum above the centre by a neck and a head (hands raised
  // beside it are as high, hands overhead higher).
  auto isFoot = [&](const Vec3d& p) { return d.floor ? d.floor->heightOf(p) < kFootHeight : up.dot(p - c) < -0.6; };
  int head = -1;
  for (const int t : tips) {
    const Vec3d& p = bodyGrid.point[t];
    const double above = up.dot(p - c);
    if (above > kHeadAbove[0] && above < kHeadAbove[1] && std::abs(p.x() - c.x()) < kHeadLateral &&
        (head < 0 || std::abs(p.x() - c.x()) < std::abs(bodyGrid.point[head].x() - c.x())))
      head = t;
  }
  if (head >= 0) d.head = bodyGrid.point[head];

  std::vector<DetectedHand> candidates;
  for (size_t k = 0; k < tips.size(); ++k) {
    const int t = tips[k];
    const Vec3d& p = bodyGrid.point[t];
    if (t == head || isFoot(p) || fromCentre[t] < o.minHandGeodesic) continue;
    // An arm hangs from a shoulder, above the hips; a leg's extremum (a knee, a foot cut off by the floor)
    // goes back down towards the hips.
    const ArmRoot root = armRoot(t, fromCentre, pred);
    if (up.dot(bodyGrid.point[root.node] - c) < kLowestArmRoot) continue;
    if (!clearOfTorso(p, c, up, d.bodyDepth, d.head)) continue;
    DetectedHand hand = handAt(bodyGrid, t, o);
    hand.geodesic = fromCentre[t];
    armSide(root, bodyGrid.point[root.node], c.x(), hand);
    // Confidence: an arm's length along the body, standing out from the rest (a shoulder bared by arms
    // crossed in front of it is an extremum too, but barely), a hand's worth of surface, a clear side.
    const double footprint = kStep * p.z() / kinect::kFx;
    const double expected = 0.5 * 3.14159 * 0.05 * 0.05 / (footprint * footprint);
    const double reach = std::clamp((hand.geodesic - o.minHandGeodesic) / 0.25, 0.0, 1.0);
    const double protrusion = std::clamp((gains[k] - kMinExtremumGain) / 0.25, 0.0, 1.0);
    hand.confidence = reach * protrusion * std::min(1.0, hand.pixels / expected) * (0.6 + 0.4 * hand.sideConfidence);
    if (hand.confidence < kMinConfidence) continue;
    candidates.push_back(hand);
  }
  dropElbows(candidates);
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const DetectedHand& a, const DetectedHand& b) { return a.confidence > b.confidence; });
  if (candidates.size() > 2) candidates.resize(2);
  d.hands = candidates;
  return d;
}

namespace {
constexpr double kFollowedFor = 0.3;         // s: a hand seen this recently is being followed
constexpr double kFollowedSideWeight = 0.2;  // of sideCost, for a followed hand
}  // namespace

HandTracker::HandTracker(const TrackerOptions& options)
    : options_(options), hold_{HandHold(options.holdTime), HandHold(options.holdTime)} {}

Vec3d HandTracker::predicted(int hand, double time) const {
  // Constant velocity for a short while, then the last position: a held hand is not carried off.
  const double dt = std::min(time - lastSeen_[hand], 0.2);
  return *last_[hand] + dt * velocity_[hand];
}

int HandTracker::sideOf(int hand) const {
  // Facing the camera, the performer's left arm leaves the torso on the camera's +x side unless mirrored.
  const int left = options_.mirrored ? -1 : 1;
  return hand == 0 ? left : -left;
}

double HandTracker::cost(int hand, double time, const DetectedHand& d, const Detection& detection) const {
  // The torso side says which hand it is when a hand is first found or found again; while a hand is followed,
  // its motion says more (arms crossed in front of the chest confuse the side), so the side only tips the
  // balance then.
  const bool followed = last_[hand] && time - lastSeen_[hand] < kFollowedFor;
  double c = 0.0;
  if (d.side != sideOf(hand)) c += (followed ? kFollowedSideWeight : 1.0) * options_.sideCost * d.sideConfidence;
  if (last_[hand]) {
    const double distance = (d.position - predicted(hand, time)).norm();
    const double reach = options_.maxHandSpeed * (time - lastSeen_[hand]) + options_.jumpMargin;
    if (distance > reach) return kInfinity;
    return c + distance;
  }
  // A first sighting: it must lie on its own side of the body when the detector could not tell the arm's side.
  if (d.sideConfidence < 0.5) {
    const double dx = d.position.x() - detection.bodyCentreX;
    if ((dx > 0.0) != (sideOf(hand) > 0)) return kInfinity;
  }
  return c + options_.newHandCost;
}

HandSample HandTracker::update(double time, const Detection& detection) {
  const auto& found = detection.hands;
  const int n = std::min(static_cast<int>(found.size()), 2);
  // Every way of giving the detections to the hands: target[i] is 0 (left), 1 (right) or -1 (neither).
  int bestTarget[2] = {-1, -1};
  double bestCost = kInfinity;
  for (int a = -1; a < 2; ++a) {
    for (int b = -1; b < 2; ++b) {
      const int target[2] = {n > 0 ? a : -1, n > 1 ? b : -1};
      if ((n < 1 && a >= 0) || (n < 2 && b >= 0)) continue;
      if (target[0] >= 0 && target[0] == target[1]) continue;
      double total = 0.0;
      bool taken[2] = {false, false};
      for (int i = 0; i < n; ++i) {
        if (target[i] < 0) continue;
        total += cost(target[i], time, found[i], detection);
        taken[target[i]] = true;
      }
      // An unused detection costs nothing; a hand left without one costs a miss.
      for (int h = 0; h < 2; ++h)
        if (!taken[h]) total += options_.missCost;
      if (total < bestCost) {
        bestCost = total;
        bestTarget[0] = target[0];
        bestTarget[1] = target[1];
      }
    }
  }
  std::optional<Vec3d> measured[2];
  double confidence[2] = {1.0, 1.0};
  for (int i = 0; i < n; ++i) {
    const int h = bestTarget[i];
    if (h < 0) continue;
    const Vec3d& p = found[i].position;
    if (last_[h]) {
      const double dt = time - lastSeen_[h];
      // A velocity from consecutive frames only; after a gap the hand starts over at rest.
      velocity_[h] = dt > 0.0 && dt < 0.2 ? Vec3d(0.5 * velocity_[h] + 0.5 * (p - *last_[h]) / dt) : Vec3d::Zero();
    }
    measured[h] = p;
    confidence[h] = found[i].confidence;
    last_[h] = p;
    lastSeen_[h] = time;
  }
  HandSample s;
  s.time = time;
  s.left = hold_[0].update(time, measured[0], confidence[0]);
  s.right = hold_[1].update(time, measured[1], confidence[1]);
  return s;
}

}  // namespace gb
