#include "collision.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

namespace gb {

namespace {

using Cell = std::array<int, 3>;

uint64_t cellKey(const Cell& c) {
  // 21 bits per axis: cells of a few centimetres cover +-20 km.
  auto bits = [](int v) { return static_cast<uint64_t>(v + (1 << 20)) & 0x1fffff; };
  return bits(c[0]) | (bits(c[1]) << 21) | (bits(c[2]) << 42);
}

Cell cellOf(const Vec3& x, float size) {
  return {static_cast<int>(std::floor(x.x() / size)), static_cast<int>(std::floor(x.y() / size)),
          static_cast<int>(std::floor(x.z() / size))};
}

bool isOneRingNeighbour(const Topology& topo, uint32_t i, uint32_t j) {
  const auto begin = topo.springNeighbour.begin() + topo.springOffset[i];
  const auto end = topo.springNeighbour.begin() + topo.springOffset[i + 1];
  return std::find(begin, end, j) != end;
}

// Living particles that are still part of the film (a particle whose triangles all tore is not).
bool inFilm(const Film& film, uint32_t i) {
  return film.state.alive[i] && film.topology.triangleOffset[i + 1] > film.topology.triangleOffset[i];
}

// A pair lies across the film when its separation makes less than 45 degrees with either normal.
constexpr float kAcrossCosineSquared = 0.5f;
constexpr float kAcrossCosine = 0.70710678f;

// What a bucket's particles look like as a piece of sheet: their bounding box, their mean normal (each normal
// turned to agree with the first: a normal's sign does not matter to the across test), how far any of their
// normals is from it, and the range of their heights along it. Most of a film's buckets hold a nearly flat piece
// of one sheet, whose particles lie along the film from any particle outside the bucket: sheetHasNoPartnerOf
// proves that from these figures, without a distance test per particle.
struct BucketSheet {
  Vec3 lower = Vec3::Constant(std::numeric_limits<float>::infinity());
  Vec3 upper = Vec3::Constant(-std::numeric_limits<float>::infinity());
  Vec3 normal = Vec3::Zero();
  float normalSpread = 0.0f;  // max over the bucket of min(|n_j - normal|, |n_j + normal|)
  float heightMin = std::numeric_limits<float>::infinity();
  float heightMax = -std::numeric_limits<float>::infinity();
};

BucketSheet summariseSheet(const std::vector<Vec3>& position, const std::vector<Vec3>& normal, size_t begin,
                           size_t end) {
  BucketSheet b;
  for (size_t k = begin; k < end; ++k) {
    b.lower = b.lower.cwiseMin(position[k]);
    b.upper = b.upper.cwiseMax(position[k]);
    b.normal += normal[k].dot(normal[begin]) < 0 ? Vec3(-normal[k]) : normal[k];
  }
  const float length = b.normal.norm();
  if (!(length > 0)) {
    b.normalSpread = std::numeric_limits<float>::infinity();  // no direction: nothing can be proved
    return b;
  }
  b.normal /= length;
  for (size_t k = begin; k < end; ++k) {
    b.normalSpread = std::max(b.normalSpread, std::min((normal[k] - b.normal).norm(), (normal[k] + b.normal).norm()));
    const float height = b.normal.dot(position[k]);
    b.heightMin = std::min(b.heightMin, height);
    b.heightMax = std::max(b.heightMax, height);
  }
  return b;
}

// True when no particle of the bucket can lie across the film from particle x (normal n): for every particle j
// there, |m . d| <= H (H its height range seen from x, m the bucket's normal) and |n_j . d| <= |m . d| + e |d|
// (e the spread of its normals), so |n_j . d| <= sqrt(1/2) |d| wherever |d| >= H / (sqrt(1/2) - e), and the same
// with n's own distance from m for |n . d|. The bucket's box keeps every |d| above its distance from x. A
// conservative proof: the lists are exactly those of testing every particle (tested against a brute-force search).
bool sheetHasNoPartnerOf(const BucketSheet& b, const Vec3& x, const Vec3& n) {
  const float tilt = std::max(b.normalSpread, std::min((n - b.normal).norm(), (n + b.normal).norm()));
  if (!(tilt < kAcrossCosine)) return false;
  const float height = b.normal.dot(x);
  // 10 um for the float rounding of heights of particles metres from the origin.
  constexpr float kRounding = 1e-5f;
  const float offPlane = std::max(b.heightMax - height, height - b.heightMin) + kRounding;
  const Vec3 outside = (b.lower - x).cwiseMax(x - b.upper).cwiseMax(0.0f);
  return outside.norm() * (kAcrossCosine - tilt) > offPlane;
}

// Particles bucketed by a hash of their grid cell, counting-sorted into one flat array: the same lookups as a
// map of cells without a heap allocation per cell. Different cells may share a bucket; the distance test
// in findContacts sorts them out.
struct CellTable {
  std::vector<uint32_t> offset;    // bucket b holds particle[offset[b] .. offset[b + 1])
  std::vector<uint32_t> particle;  // particle ids, ascending within each bucket
  // Their positions and normals in the same order: the search streams through these instead of
  // gathering from the state's arrays, which is most of its time on a large film.
  std::vector<Vec3> position;
  std::vector<Vec3> normal;
  std::vector<float> speed;  // about the film's mean velocity
  // Each occupied bucket's sheet: bucket b's is sheet[sheetIndex[b]] (the occupied buckets are few: a bucket
  // holds a cell of tens to thousands of particles).
  std::vector<uint32_t> sheetIndex;
  std::vector<BucketSheet> sheet;
  uint64_t mask = 0;

  [[nodiscard]] uint32_t bucketOf(const Cell& c) const {
    return static_cast<uint32_t>((cellKey(c) * 0x9E3779B97F4A7C15ull) >> 32 & mask);
  }
};

CellTable bucketParticles(const Film& film, const std::vector<float>& speed, float cellSize) {
  const State& s = film.state;
  const size_t n = s.size();
  CellTable table;
  size_t buckets = 1;
  while (buckets < 2 * n) buckets *= 2;
  table.mask = buckets - 1;
  std::vector<uint32_t> bucket(n, 0u);
  table.offset.assign(buckets + 1, 0u);
  for (uint32_t i = 0; i < n; ++i)
    if (inFilm(film, i)) ++table.offset[(bucket[i] = table.bucketOf(cellOf(s.position.get(i), cellSize))) + 1];
  for (size_t b = 0; b < buckets; ++b) table.offset[b + 1] += table.offset[b];
  table.particle.resize(table.offset[buckets]);
  std::vector<uint32_t> fill(table.offset.begin(), table.offset.end() - 1);
  for (uint32_t i = 0; i < n; ++i)
    if (inFilm(film, i)) table.particle[fill[bucket[i]]++] = i;
  table.position.resize(table.particle.size());
  table.normal.resize(table.particle.size());
  table.speed.resize(table.particle.size());
  for (size_t k = 0; k < table.particle.size(); ++k) {
    table.speed[k] = speed[table.particle[k]];
    table.position[k] = s.position.get(table.particle[k]);
    table.normal[k] = s.normal.get(table.particle[k]);
  }
  table.sheetIndex.assign(buckets, 0u);
  for (size_t b = 0; b < buckets; ++b) {
    if (table.offset[b] == table.offset[b + 1]) continue;
    table.sheetIndex[b] = static_cast<uint32_t>(table.sheet.size());
    table.sheet.push_back(summariseSheet(table.position, table.normal, table.offset[b], table.offset[b + 1]));
  }
  return table;
}

std::vector<float> speedsAboutTheMean(const Film& film) {
  const State& s = film.state;
  Vec3 sum = Vec3::Zero();
  size_t living = 0;
  for (uint32_t i = 0; i < s.size(); ++i)
    if (inFilm(film, i)) {
      sum += s.velocity.get(i);
      ++living;
    }
  const Vec3 mean = living ? Vec3(sum / static_cast<float>(living)) : Vec3::Zero();
  std::vector<float> speed(s.size(), 0.0f);
  for (uint32_t i = 0; i < s.size(); ++i)
    if (inFilm(film, i)) speed[i] = (s.velocity.get(i) - mean).norm();
  return speed;
}

// The rest distance pair (i, j) had in the last list, or 0 when it was not listed.
float previousRestDistance(const ContactHistory& history, uint32_t i, uint32_t j) {
  const std::vector<uint32_t>& c = history.contacts;
  const size_t n = history.particles;
  if (i >= n || j >= n || c.size() < n + 1) return 0.0f;
  const auto first = c.begin() + static_cast<ptrdiff_t>(n + 1 + c[i]),
             last = c.begin() + static_cast<ptrdiff_t>(n + 1 + c[i + 1]);
  const auto found = std::lower_bound(first, last, j);
  if (found == last || *found != j) return 0.0f;
  return contactRestDistance(c, n, static_cast<uint32_t>(found - c.begin() - static_cast<ptrdiff_t>(n + 1)));
}

}  // namespace

float contactRestDistanceAfter(const Params& p, float previousRest, float separation) {
  return std::min(p.collisionDistance, std::max(previousRest, separation));
}

size_t findContacts(const Params& p, float frameTime, float slack, Film& film, const ContactHistory& history) {
  const State& s = film.state;
  Topology& topo = film.topology;
  const size_t n = s.size();
  // Two particles close at most |v_i - v_j| <= |v_i - mean| + |v_j - mean| in a frame: a bubble flying as a whole
  // needs no wider search than one at rest, and each pair only its own reach.
  const std::vector<float> speed = speedsAboutTheMean(film);
  auto margin = [&](float speeds) { return std::min(kMaxContactMargin, frameTime * speeds + slack); };
  const float fastest = n ? *std::max_element(speed.begin(), speed.end()) : 0.0f;
  const float reach = p.collisionDistance + margin(2.0f * fastest);
  std::vector<std::vector<uint32_t>> lists(n);
  if (reach > 0 && p.collisionStiffness > 0) {
    const CellTable table = bucketParticles(film, speed, reach);
    const float reachSquared = reach * reach;
    // Each particle lists its partners of higher index from the read-only table (each pair once, half the
    // distance tests): parallel, and the same lists in any order.
#pragma omp parallel for schedule(dynamic, 256)
    for (uint32_t i = 0; i < n; ++i) {
      if (!inFilm(film, i)) continue;
      const Vec3 xi = s.position.get(i), ni = s.normal.get(i);
      const Cell c = cellOf(xi, reach);
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            const uint32_t bucket = table.bucketOf({c[0] + dx, c[1] + dy, c[2] + dz});
            if (table.offset[bucket] == table.offset[bucket + 1] ||
                sheetHasNoPartnerOf(table.sheet[table.sheetIndex[bucket]], xi, ni))
              continue;
            const auto bucketEnd = table.particle.begin() + table.offset[bucket + 1];
            const auto higher = std::upper_bound(table.particle.begin() + table.offset[bucket], bucketEnd, i);
            for (auto k = static_cast<size_t>(higher - table.particle.begin()); k < table.offset[bucket + 1]; ++k) {
              const uint32_t j = table.particle[k];
              // Squared lengths throughout: most candidates are the film's own in-plane neighbours,
              // rejected here without a square root.
              const Vec3 d = table.position[k] - xi;
              const float lengthSquared = d.squaredNorm();
              if (!(lengthSquared < reachSquared) || lengthSquared <= 0) continue;
              const float pairReach = p.collisionDistance + margin(speed[i] + table.speed[k]);
              if (!(lengthSquared < pairReach * pairReach)) continue;
              const float alongI = ni.dot(d), alongJ = table.normal[k].dot(d);
              const bool across = alongI * alongI > kAcrossCosineSquared * lengthSquared ||
                                  alongJ * alongJ > kAcrossCosineSquared * lengthSquared;
              if (across && !isOneRingNeighbour(topo, i, j)) lists[i].push_back(j);
            }
          }
      // Two of the 27 cells can share a bucket (a hash collision): sorting and removing repeats keeps the
      // lists the same however the table falls.
      std::sort(lists[i].begin(), lists[i].end());
      lists[i].erase(std::unique(lists[i].begin(), lists[i].end()), lists[i].end());
    }
  }
  // Each particle's partners of lower index, in ascending order because i ascends.
  std::vector<std::vector<uint32_t>> lower(n);
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j : lists[i]) lower[j].push_back(i);
  std::vector<uint32_t> packed(n + 1, 0u);
  size_t total = 0;
  for (size_t i = 0; i < n; ++i) {
    packed[i] = static_cast<uint32_t>(total);
    total += lower[i].size() + lists[i].size();
  }
  packed[n] = static_cast<uint32_t>(total);
  packed.reserve(n + 1 + 2 * total);
  for (size_t i = 0; i < n; ++i) {
    packed.insert(packed.end(), lower[i].begin(), lower[i].end());
    packed.insert(packed.end(), lists[i].begin(), lists[i].end());
  }
  packed.resize(n + 1 + 2 * total);
#pragma omp parallel for schedule(dynamic, 256)
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t k = packed[i]; k < packed[i + 1]; ++k) {
      const uint32_t j = packed[n + 1 + k];
      const float separation = (s.position.get(i) - s.position.get(j)).norm();
      const float rest = contactRestDistanceAfter(p, previousRestDistance(history, i, j), separation);
      packed[n + 1 + total + k] = std::bit_cast<uint32_t>(rest);
    }
  topo.contacts = std::move(packed);
  return total / 2;
}

float impactNumber(const Params& params, float approachSpeed, float elasticity) {
  if (approachSpeed <= 0.0f || elasticity <= 0.0f) return 0.0f;
  return params.filmInertia * approachSpeed * approachSpeed / elasticity;
}

Impact hardestImpact(const Params& params, float frameTime, const Film& film) {
  const State& s = film.state;
  const std::vector<uint32_t>& contacts = film.topology.contacts;
  const size_t n = s.size();
  Impact hardest;
  if (contacts.size() <= n) return hardest;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t k = contacts[i]; k < contacts[i + 1]; ++k) {
      const uint32_t j = contacts[n + 1 + k];
      if (j < i || !s.alive[i] || !s.alive[j]) continue;  // each pair once
      const Vec3 d = s.position.get(j) - s.position.get(i);
      const float distance = d.norm();
      if (distance <= 0.0f) continue;
      const float approach = -(s.velocity.get(j) - s.velocity.get(i)).dot(d) / distance;
      if (!(distance - approach * frameTime < params.collisionDistance)) continue;  // no contact this frame
      const float number = impactNumber(params, approach, 0.5f * (s.elasticity[i] + s.elasticity[j]));
      if (number <= hardest.number) continue;
      hardest.number = number;
      hardest.particle = s.velocity.get(i).squaredNorm() >= s.velocity.get(j).squaredNorm() ? i : j;
    }
  return hardest;
}

Nearest nearestParticle(const State& s, const Vec3& x) {
  Nearest nearest{0, std::numeric_limits<float>::infinity()};
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s.alive[i]) continue;
    const float d = (s.position.get(i) - x).norm();
    if (d < nearest.distance) nearest = {i, d};
  }
  return nearest;
}

double windingNumber(const Film& film, const Vec3& x) {
  const Topology& topo = film.topology;
  double solidAngle = 0;
  for (size_t t = 0; t < topo.triangleCount(); ++t) {
    const Eigen::Vector3d a = (film.state.position.get(topo.triangles[3 * t]) - x).cast<double>();
    const Eigen::Vector3d b = (film.state.position.get(topo.triangles[3 * t + 1]) - x).cast<double>();
    const Eigen::Vector3d c = (film.state.position.get(topo.triangles[3 * t + 2]) - x).cast<double>();
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    solidAngle += 2.0 * std::atan2(numerator, denominator);
  }
  return solidAngle / (4.0 * 3.14159265358979323846);
}

}  // namespace gb
