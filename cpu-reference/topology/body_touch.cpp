#include "topology/body_touch.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gb {

namespace {

// How far the body may move between two depth frames and still be measured closing on a particle: 3 m/s over a 30 Hz
// camera's frame, twice the strike speed. A faster approach is measured as this one, which is enough to tell a strike.
constexpr float kLongestStrike = 0.1f;

// Rounds of the wet push for one particle: out of one point's reach, then out of the next's.
constexpr int kPushRounds = 4;

// Every n-th point, so that at most `most` remain, spread over the whole body.
std::vector<Vec3> thinned(std::vector<Vec3> points, size_t most) {
  if (most == 0 || points.size() <= most) return points;
  std::vector<Vec3> kept;
  kept.reserve(most);
  const double stride = static_cast<double>(points.size()) / static_cast<double>(most);
  for (size_t k = 0; k < most; ++k) kept.push_back(points[static_cast<size_t>(static_cast<double>(k) * stride)]);
  return kept;
}

}  // namespace

BodyGrid::BodyGrid(const std::vector<Vec3>& points, float cell) {
  if (points.empty() || !(cell > 0.0f)) return;
  Vec3 lower = Vec3::Constant(std::numeric_limits<float>::infinity()), upper = -lower;
  for (const Vec3& p : points) lower = lower.cwiseMin(p), upper = upper.cwiseMax(p);
  const Vec3 extent = upper - lower;
  cell_ = cell;
  // A cloud spread wider than the grid may hold at this cell size gets larger cells (queries stay exact).
  while (static_cast<double>(extent.x() / cell_ + 1) * (extent.y() / cell_ + 1) * (extent.z() / cell_ + 1) >
         static_cast<double>(kMaxCells))
    cell_ *= 2.0f;
  lower_ = lower;
  for (int a = 0; a < 3; ++a) cells_[a] = static_cast<int>(extent[a] / cell_) + 1;
  const size_t n = static_cast<size_t>(cells_[0]) * cells_[1] * cells_[2];
  // Counting sort of the points by cell: cellStart_ holds each cell's first point.
  std::vector<uint32_t> cellOfPoint(points.size());
  cellStart_.assign(n + 1, 0);
  for (size_t p = 0; p < points.size(); ++p) {
    std::array<int, 3> c{};
    (void)cellOf(points[p], 0, c);  // inside: the box is the points' own
    cellOfPoint[p] = static_cast<uint32_t>(index(c[0], c[1], c[2]));
    ++cellStart_[cellOfPoint[p] + 1];
  }
  for (size_t c = 0; c < n; ++c) cellStart_[c + 1] += cellStart_[c];
  std::vector<uint32_t> next(cellStart_.begin(), cellStart_.end() - 1);
  points_.resize(points.size());
  for (size_t p = 0; p < points.size(); ++p) points_[next[cellOfPoint[p]]++] = points[p];
}

bool BodyGrid::cellOf(const Vec3& x, int rings, std::array<int, 3>& cell) const {
  for (int a = 0; a < 3; ++a) {
    const float f = std::floor((x[a] - lower_[a]) / cell_);
    if (!(f >= static_cast<float>(-rings) && f < static_cast<float>(cells_[a] + rings))) return false;
    cell[a] = static_cast<int>(f);
  }
  return true;
}

size_t BodyGrid::index(int i, int j, int k) const { return (static_cast<size_t>(k) * cells_[1] + j) * cells_[0] + i; }

template <class Visit>
void BodyGrid::visitShell(const std::array<int, 3>& c, int ring, Visit&& visit) const {
  for (int k = std::max(c[2] - ring, 0); k <= std::min(c[2] + ring, cells_[2] - 1); ++k)
    for (int j = std::max(c[1] - ring, 0); j <= std::min(c[1] + ring, cells_[1] - 1); ++j) {
      const bool face = std::abs(k - c[2]) == ring || std::abs(j - c[1]) == ring;
      // Inside the shell's faces along k and j only its two ends along i belong to it.
      const int step = face ? 1 : std::max(2 * ring, 1);
      for (int i = c[0] - ring; i <= c[0] + ring; i += step) {
        if (i < 0 || i >= cells_[0]) continue;
        const size_t cell = index(i, j, k);
        for (uint32_t p = cellStart_[cell]; p < cellStart_[cell + 1]; ++p) visit(points_[p]);
      }
    }
}

std::optional<Vec3> BodyGrid::nearestPoint(const Vec3& x, float reach) const {
  if (points_.empty()) return std::nullopt;
  const int rings = static_cast<int>(std::ceil(reach / cell_));
  std::array<int, 3> c{};
  if (!cellOf(x, rings, c)) return std::nullopt;  // farther than reach from the box of the points
  float best = reach * reach;
  std::optional<Vec3> nearest;
  // Shells of cells around x's, nearest first: every point of shell r lies at least (r - 1) cells away.
  for (int ring = 0; ring <= rings; ++ring) {
    const float closest = static_cast<float>(ring - 1) * cell_;
    if (ring > 1 && closest * closest > best) break;
    visitShell(c, ring, [&](const Vec3& p) {
      const float d = (p - x).squaredNorm();
      if (d <= best) best = d, nearest = p;
    });
  }
  return nearest;
}

std::optional<float> BodyGrid::nearestWithin(const Vec3& x, float reach) const {
  const std::optional<Vec3> p = nearestPoint(x, reach);
  return p ? std::optional<float>((*p - x).norm()) : std::nullopt;
}

void BodyTouch::setBody(const BodyPoints& body) {
  std::vector<Vec3> kept;
  kept.reserve(body.points.size());
  for (const Vec3& p : body.points)
    if (p.allFinite()) kept.push_back(p);
  kept = thinned(std::move(kept), options_.maxPoints);
  // The newest frame becomes the frame before, asked how far the body was from a particle the new one touches.
  before_ = std::move(now_);
  beforeTime_ = nowTime_;
  now_ = BodyGrid(kept, options_.distance);
  nowTime_ = body.time;
  grips_.clear();
  for (const Vec3& g : body.grips)
    if (g.allFinite()) grips_.push_back(g);
}

bool BodyTouch::atGrip(const Vec3& x) const {
  const float grip2 = options_.gripRadius * options_.gripRadius;
  return std::any_of(grips_.begin(), grips_.end(), [&](const Vec3& g) { return (x - g).squaredNorm() < grip2; });
}

void BodyTouch::clear() {
  now_ = BodyGrid();
  before_ = BodyGrid();
  grips_.clear();
}

std::vector<Touch> BodyTouch::touches(const State& state, std::vector<uint8_t>& armed, bool onTheWire) const {
  std::vector<Touch> touching;
  armed.resize(state.size(), 0);
  const double interval = nowTime_ - beforeTime_;
  for (size_t i = 0; i < state.size(); ++i) {
    if (!state.alive[i]) continue;
    const Vec3 x = state.position.get(i);
    if (onTheWire && atGrip(x)) continue;
    if (!armed[i]) {  // made inside the body: armed once drawn clear of it, by a margin the body's jitter never spans
      armed[i] = now_.empty() || !now_.nearestPoint(x, options_.armDistance);
      continue;
    }
    const std::optional<Vec3> nearest = now_.empty() ? std::nullopt : now_.nearestPoint(x, options_.distance);
    if (!nearest) continue;
    Touch t{i, x, 0.0f};
    const float gap = (*nearest - x).norm();
    // The body's part: how much nearer it came over its last frame interval (from as far as it can have come).
    if (!before_.empty() && interval > 0.0) {
      const float farthest = options_.distance + kLongestStrike;
      const float was = before_.nearestWithin(x, farthest).value_or(farthest);
      t.approachSpeed = std::max(0.0f, static_cast<float>((was - gap) / interval));
    }
    // The particle's own part: its velocity towards the point it touches.
    if (gap > 0.0f) t.approachSpeed += std::max(0.0f, state.velocity.get(i).dot((*nearest - x) / gap));
    touching.push_back(t);
  }
  std::sort(touching.begin(), touching.end(),
            [](const Touch& a, const Touch& b) { return a.approachSpeed > b.approachSpeed; });
  return touching;
}

size_t BodyTouch::push(State& state, const std::vector<Touch>& touching) const {
  size_t moved = 0;
  for (const Touch& t : touching) {
    // Out of the nearest point's reach may be into the next one's (a particle at a palm's edge): a few rounds.
    bool pushed = false;
    for (int round = 0; round < kPushRounds; ++round) {
      const Vec3 x = state.position.get(t.particle);
      const std::optional<Vec3> nearest = now_.nearestPoint(x, options_.distance);
      if (!nearest) break;
      const Vec3 away = x - *nearest;
      const float gap = away.norm();
      if (gap >= options_.distance) break;
      // A particle exactly on a point has no way out of its own: it goes back along its velocity.
      const Vec3 v = state.velocity.get(t.particle);
      const Vec3 out = gap > 1e-6f ? Vec3(away / gap) : (v.norm() > 1e-6f ? Vec3(-v.normalized()) : Vec3::UnitZ());
      state.position.set(t.particle, *nearest + options_.distance * out);
      const float into = v.dot(-out);
      if (into > 0.0f) state.velocity.set(t.particle, v + into * out);
      pushed = true;
    }
    moved += pushed ? 1 : 0;
  }
  return moved;
}

std::optional<Touch> BodyTouch::burstingTouch(const std::vector<Touch>& touching) const {
  if (touching.empty()) return std::nullopt;
  if (!options_.wetHands) return touching.front();
  if (touching.front().approachSpeed > options_.strikeSpeed) return touching.front();
  return std::nullopt;
}

}  // namespace gb
