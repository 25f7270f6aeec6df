#include "topology/collision.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <span>

#include "solver/float_lanes.h"

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

// Passes over every particle that are cheap per particle (the table's, the speeds') run in parallel only on films
// this large: on a small film the threads' start and join cost more than the pass, and a busy core can hold the
// join for a whole time slice.
constexpr size_t kParallelPass = size_t{1} << 16;

// What a bucket's particles look like as a piece of sheet: their bounding box, their mean normal (each normal
// turned to agree with the first: a normal's sign does not matter to the across test), how far any of their
// normals is from it, and the range of their heights along it. Most of a film's buckets hold a nearly flat piece
// of one sheet, whose particles lie along the film from any particle farther than partnerRadius: the search
// proves that from these figures, without a distance test per particle.
struct BucketSheet {
  Vec3 lower = Vec3::Constant(std::numeric_limits<float>::infinity());
  Vec3 upper = Vec3::Constant(-std::numeric_limits<float>::infinity());
  Vec3 normal = Vec3::Zero();
  float normalSpread = 0.0f;  // max over the bucket of min(|n_j - normal|, |n_j + normal|)
  float heightMin = std::numeric_limits<float>::infinity();
  float heightMax = -std::numeric_limits<float>::infinity();
  Vec3 sortDirection = Vec3::UnitX();  // along which the bucket's particles are sorted (sortDirectionOf)
  // Its height range over sqrt(1/2) - its spread: the partner radius seen from one of its own particles with its
  // mean normal; infinite when nothing can be proved. It only chooses which side of a pair searches (searchedFrom).
  float ownRadius = std::numeric_limits<float>::infinity();
};

// A unit direction in the plane of the box's two longest sides, turned off both axes by an irrational slope
// (sqrt 2 - 1): a film's particles sit on a lattice whose rows often follow an axis, and sorted along an axis, the
// slab about a particle would hold a whole column of the lattice; sorted along this direction it holds only the
// particles within its width.
Vec3 sortDirectionOf(const Vec3& extent) {
  int longest = 0;
  extent.maxCoeff(&longest);
  const int second = extent[(longest + 1) % 3] >= extent[(longest + 2) % 3] ? (longest + 1) % 3 : (longest + 2) % 3;
  Vec3 direction = Vec3::Zero();
  direction[longest] = 1.0f;
  direction[second] = 0.41421356f;
  return direction.normalized();
}

BucketSheet summariseSheet(const std::vector<Vec3>& position, const std::vector<Vec3>& normal, size_t begin,
                           size_t end) {
  BucketSheet b;
  for (size_t k = begin; k < end; ++k) {
    b.lower = b.lower.cwiseMin(position[k]);
    b.upper = b.upper.cwiseMax(position[k]);
    b.normal += normal[k].dot(normal[begin]) < 0 ? Vec3(-normal[k]) : normal[k];
  }
  b.sortDirection = sortDirectionOf(b.upper - b.lower);
  const float length = b.normal.norm();
  if (!(length > 0)) {
    b.normalSpread = std::numeric_limits<float>::infinity();  // no direction: nothing can be proved
    return b;
  }
  b.normal /= length;
  for (size_t k = begin; k < end; ++k) {
    b.normalSpread =
        std::max(b.normalSpread, std::min((normal[k] - b.normal).squaredNorm(), (normal[k] + b.normal).squaredNorm()));
    const float height = b.normal.dot(position[k]);
    b.heightMin = std::min(b.heightMin, height);
    b.heightMax = std::max(b.heightMax, height);
  }
  b.normalSpread = std::sqrt(b.normalSpread);  // the largest squared distance, rooted once
  b.ownRadius = (b.heightMax - b.heightMin) / (kAcrossCosine - b.normalSpread);
  if (!(b.normalSpread < kAcrossCosine && b.ownRadius >= 0)) b.ownRadius = std::numeric_limits<float>::infinity();
  return b;
}

// A distance from particle x (normal n) beyond which no particle of the bucket lies across the film from it
// (infinite when nothing can be proved). For every particle j there, with d = x_j - x, m the bucket's normal and H
// the bucket's height range along m seen from x (max(heightMax - m.x, m.x - heightMin)):
//   |m . d| <= H and |n_j . d| <= |m . d| + |n_j -+ m| |d| <= H + e |d|   (e the spread of the bucket's normals),
// and the same with t = |n -+ m| for |n . d|. With tilt = max(e, t) < sqrt(1/2), a partner needs
// sqrt(1/2) |d| < max(|n_j . d|, |n . d|) <= H + tilt |d|, so |d| < H / (sqrt(1/2) - tilt). Nothing assumes x lies
// outside the bucket: in its own cell of a nearly flat sheet (H of micrometres) a particle's partners can only be
// its closest neighbours or none. H carries 10 um for the float rounding of heights of particles metres from the
// origin, which also keeps sqrt(1/2) |d| - |n_j . d| >= 10 um beyond the radius, far above the float error of the
// search's own across test on a separation of centimetres. Four particles at a time, coordinates by axis.
Float4 partnerRadius(const BucketSheet& b, const std::array<Float4, 3>& x, const std::array<Float4, 3>& n) {
  Float4 towards(0.0f), away(0.0f), height(0.0f);  // |n - m|^2, |n + m|^2, m . x
  for (int a = 0; a < 3; ++a) {
    const Float4 m(b.normal[a]);
    towards = towards + (n[a] - m) * (n[a] - m);
    away = away + (n[a] + m) * (n[a] + m);
    height = height + m * x[a];
  }
  const Float4 tilt = max(Float4(b.normalSpread), sqrt(min(towards, away)));
  constexpr float kRounding = 1e-5f;
  const Float4 offPlane = max(Float4(b.heightMax) - height, height - Float4(b.heightMin)) + Float4(kRounding);
  const Float4 across(kAcrossCosine);
  return select(tilt < across, offPlane / (across - tilt), Float4(std::numeric_limits<float>::infinity()));
}

// Particles bucketed by a hash of their grid cell, counting-sorted into one flat array: the same lookups as a
// map of cells without a heap allocation per cell. Different cells may share a bucket; the distance test
// in findContacts sorts them out. Within a bucket the particles are sorted along the bucket's sort direction, so
// that a search within a radius r of a particle reads only the slab of the bucket 2 r wide about it.
struct CellTable {
  std::vector<uint32_t> offset;    // bucket b holds particle[offset[b] .. offset[b + 1])
  std::vector<uint32_t> particle;  // particle ids, sorted along their bucket's sort direction
  // Their positions and normals in the same order: the search streams through these instead of
  // gathering from the state's arrays, which is most of its time on a large film.
  std::vector<Vec3> position;
  std::vector<Vec3> normal;
  // The positions and normals again, and the velocities, one array per axis for the search's four-wide test.
  // These and `along` hold kLoadPast entries more than the table, so that four entries may be loaded from any one.
  std::array<std::vector<float>, 3> x, n, v;
  std::vector<float> along;  // the coordinate along the bucket's sort direction, ascending within each bucket
  std::vector<float> reach;  // how far from each entry a partner of it can lie (its particle's reach, find)
  static constexpr size_t kLoadPast = 3;
  // The occupied buckets in ascending order, and each one's sheet: bucket occupied[o]'s is sheet[o], and
  // bucket b's is sheet[sheetIndex[b]] (a bucket holds a cell of tens to thousands of particles).
  std::vector<uint32_t> occupied;
  std::vector<uint32_t> sheetIndex;
  std::vector<BucketSheet> sheet;
  uint64_t mask = 0;
  std::vector<uint32_t> bucket;  // each particle's bucket, while the table is built

  [[nodiscard]] uint32_t bucketOf(const Cell& c) const {
    return static_cast<uint32_t>((cellKey(c) * 0x9E3779B97F4A7C15ull) >> 32 & mask);
  }
};

// The living particles of the film: their bounding box, their number and their area.
struct FilmExtent {
  Vec3 lower, upper;
  size_t living = 0;
  double area = 0;
};

FilmExtent extentOf(const Film& film) {
  const State& s = film.state;
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  float lx = kInfinity, ly = kInfinity, lz = kInfinity, ux = -kInfinity, uy = -kInfinity, uz = -kInfinity;
  size_t living = 0;
  double area = 0;
#pragma omp parallel for schedule(static) if (s.size() >= kParallelPass) reduction(min : lx, ly, lz) \
    reduction(max : ux, uy, uz) reduction(+ : living, area)
  for (size_t i = 0; i < s.size(); ++i)
    if (inFilm(film, static_cast<uint32_t>(i))) {
      lx = std::min(lx, s.position.x[i]), ly = std::min(ly, s.position.y[i]), lz = std::min(lz, s.position.z[i]);
      ux = std::max(ux, s.position.x[i]), uy = std::max(uy, s.position.y[i]), uz = std::max(uz, s.position.z[i]);
      ++living;
      area += s.voronoiArea[i];
    }
  return {Vec3(lx, ly, lz), Vec3(ux, uy, uz), living, area};
}

// The width of the search's cells: the reach, or kCellSpacings particle spacings (the square root of the mean area
// a particle holds) where that is wider. Any width of at least the reach finds the same pairs, in the 27 cells about
// a particle's own; the width sets the work. Each cell costs a look-up of its 27 neighbours, and each four of its
// particles a test against every bucket they fill. A smooth sheet crosses a cell of c spacings in about c^2
// particles: on the default run's free bubble, cells of one reach (3 cm, two spacings) hold about four, and the
// per-cell costs are most of the search; at three spacings they hold about ten, and the search takes a fifth less
// time. Wider cells cost more in slab searches than they save. A film whose reach is wider (a fast stroke) keeps it.
float cellSizeFor(const FilmExtent& extent, float reach) {
  constexpr float kCellSpacings = 3.0f;
  if (extent.living == 0) return reach;
  const auto spacing = static_cast<float>(std::sqrt(extent.area / static_cast<double>(extent.living)));
  if (!std::isfinite(spacing)) return reach;  // the areas of a film gone wrong: no guide to its particles' density
  return std::max(reach, kCellSpacings * spacing);
}

// Twice the number of cells the film can occupy (its particles, or the cells of its bounding box if fewer), as a
// power of two: a table that stays in cache on a large flat film, with few cells sharing a bucket.
size_t bucketCount(const FilmExtent& extent, float cellSize) {
  double cells = static_cast<double>(extent.living);
  if (extent.living) {
    const Cell first = cellOf(extent.lower, cellSize), last = cellOf(extent.upper, cellSize);
    double boxCells = 1;
    for (int a = 0; a < 3; ++a) boxCells *= static_cast<double>(last[a]) - first[a] + 1;
    cells = std::min(cells, boxCells);
  }
  size_t buckets = 1;
  while (static_cast<double>(buckets) < 2 * cells) buckets *= 2;
  return buckets;
}

// Fills the table's entries [begin, end) of one bucket: their positions, normals and velocities, the bucket's sheet,
// and the order along its sort direction (ties by id keep the table the same on every run). `order` is scratch
// memory, kept by the caller from one bucket to the next.
void sortBucketAlongItsSheet(const State& s, std::span<const float> particleReach, size_t begin, size_t end,
                             BucketSheet& sheet, CellTable& table, std::vector<std::pair<float, uint32_t>>& order) {
  for (size_t k = begin; k < end; ++k) {
    table.position[k] = s.position.get(table.particle[k]);
    table.normal[k] = s.normal.get(table.particle[k]);
  }
  sheet = summariseSheet(table.position, table.normal, begin, end);
  order.resize(end - begin);
  for (size_t k = begin; k < end; ++k) {
    // A particle at NaN (no one's partner) sorts last: NaN keys would break the sort's ordering.
    const float along = sheet.sortDirection.dot(table.position[k]);
    order[k - begin] = {std::isnan(along) ? std::numeric_limits<float>::infinity() : along, table.particle[k]};
  }
  std::sort(order.begin(), order.end());
  for (size_t k = begin; k < end; ++k) {
    const uint32_t i = order[k - begin].second;
    table.particle[k] = i;
    table.along[k] = order[k - begin].first;
    table.reach[k] = particleReach[i];
    table.position[k] = s.position.get(i);
    table.normal[k] = s.normal.get(i);
    for (int a = 0; a < 3; ++a) {
      table.x[a][k] = table.position[k][a];
      table.n[a][k] = table.normal[k][a];
      table.v[a][k] = s.velocity.get(i)[a];
    }
  }
}

// Fills `table` (its arrays keep their memory from the last time).
void bucketParticles(const Film& film, std::span<const float> particleReach, const FilmExtent& extent, float cellSize,
                     CellTable& table) {
  const State& s = film.state;
  const size_t n = s.size();
  const size_t buckets = bucketCount(extent, cellSize);
  table.mask = buckets - 1;
  std::vector<uint32_t>& bucket = table.bucket;
  constexpr uint32_t kNotInFilm = std::numeric_limits<uint32_t>::max();
  bucket.assign(n, kNotInFilm);
#pragma omp parallel for schedule(static) if (n >= kParallelPass)
  for (size_t i = 0; i < n; ++i)
    if (inFilm(film, static_cast<uint32_t>(i))) bucket[i] = table.bucketOf(cellOf(s.position.get(i), cellSize));
  table.offset.assign(buckets + 1, 0u);
  for (uint32_t i = 0; i < n; ++i)
    if (bucket[i] != kNotInFilm) ++table.offset[bucket[i] + 1];
  for (size_t b = 0; b < buckets; ++b) table.offset[b + 1] += table.offset[b];
  table.particle.resize(table.offset[buckets]);
  std::vector<uint32_t> fill(table.offset.begin(), table.offset.end() - 1);
  for (uint32_t i = 0; i < n; ++i)
    if (bucket[i] != kNotInFilm) table.particle[fill[bucket[i]]++] = i;
  table.position.resize(table.particle.size());
  table.normal.resize(table.particle.size());
  for (auto* arrays : {&table.x, &table.n, &table.v})
    for (std::vector<float>& axis : *arrays) axis.resize(table.particle.size() + CellTable::kLoadPast);
  table.along.resize(table.particle.size() + CellTable::kLoadPast);
  table.reach.resize(table.particle.size() + CellTable::kLoadPast);
  table.sheetIndex.assign(buckets, 0u);
  table.occupied.clear();
  for (uint32_t b = 0; b < buckets; ++b) {
    if (table.offset[b] == table.offset[b + 1]) continue;
    table.sheetIndex[b] = static_cast<uint32_t>(table.occupied.size());
    table.occupied.push_back(b);
  }
  table.sheet.resize(table.occupied.size());
#pragma omp parallel if (n >= kParallelPass)
  {
    std::vector<std::pair<float, uint32_t>> order;
#pragma omp for schedule(dynamic, 1)
    for (size_t o = 0; o < table.occupied.size(); ++o) {
      const uint32_t b = table.occupied[o];
      sortBucketAlongItsSheet(s, particleReach, table.offset[b], table.offset[b + 1], table.sheet[o], table, order);
    }
  }
}

// Whether the pairs between the particles of buckets `home` and b are listed from home's (else from b's): from the
// bucket whose neighbour has the smaller intrinsic partner radius (ties by index), so that a flat cell beside a
// folded one is searched from the fold, where its radius skips most of it, and not the other way round. Both
// buckets answer alike, so every pair is listed exactly once.
bool searchedFrom(const CellTable& table, uint32_t home, uint32_t b) {
  const float radiusHome = table.sheet[table.sheetIndex[home]].ownRadius;
  const float radiusB = table.sheet[table.sheetIndex[b]].ownRadius;
  return radiusB < radiusHome || (radiusB == radiusHome && b > home);
}

// A thousandth and 10 um more than a reach or a partner radius, for the float rounding of the coordinates compared
// with it.
template <class F>
F widened(F r) {
  return r * F(1.001f) + F(1e-5f);
}

// Applies PartnerRule::listRunPartners's first two tests (a particle farther from bucket b's box than its reach, at
// most the search's `reach`, or than the partner radius b's sheet allows it, lists nothing there) to all of bucket
// `home`'s particles at once: false when every one of them would fail them. Their distance to b's box is at least the
// gap between the two boxes, and partnerRadius is at most its bound over home's box (heights along b's normal) and
// normals (home's mean normal and spread). The bound is widened by 1% and 20 um for the float rounding of the sums it
// is made of, which round differently from the per-particle ones. On a film's flat stretches this drops 26 of the 27
// cells' buckets (all but home) without a test per particle.
bool bucketMayHold(const CellTable& table, uint32_t home, uint32_t b, float reach) {
  const BucketSheet& from = table.sheet[table.sheetIndex[home]];
  const BucketSheet& sheet = table.sheet[table.sheetIndex[b]];
  const float gapSquared = (sheet.lower - from.upper).cwiseMax(from.lower - sheet.upper).cwiseMax(0.0f).squaredNorm();
  if (gapSquared > widened(reach) * widened(reach)) return false;  // a NaN gap compares false: searched
  const Vec3& m = sheet.normal;
  const float turn = std::sqrt(std::min((from.normal - m).squaredNorm(), (from.normal + m).squaredNorm()));
  const float tilt = std::max(sheet.normalSpread, from.normalSpread + turn) + 1e-5f;
  if (!(tilt < kAcrossCosine)) return true;
  float lowest = 0.0f, highest = 0.0f;  // of m . x over home's box
  for (int a = 0; a < 3; ++a) {
    lowest += std::min(m[a] * from.lower[a], m[a] * from.upper[a]);
    highest += std::max(m[a] * from.lower[a], m[a] * from.upper[a]);
  }
  const float offPlane = std::max(sheet.heightMax - lowest, highest - sheet.heightMin) + 1e-5f;
  const float radius = widened(std::min(reach, 1.01f * (offPlane + 2e-5f) / (kAcrossCosine - tilt)));
  return !(gapSquared > radius * radius);
}

// The distinct occupied buckets of the 27 cells about cell c (in bucket `home`) that its particles search: home
// and those searched from it (searchedFrom) that may hold a partner of one of them (bucketMayHold). Every partner
// of a particle in c lies in the 27; returns their number.
size_t bucketsAround(const CellTable& table, uint32_t home, const Cell& c, float reach,
                     std::array<uint32_t, 27>& around) {
  size_t count = 0;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const uint32_t b = table.bucketOf({c[0] + dx, c[1] + dy, c[2] + dz});
        // Two of the 27 cells can share a bucket (a hash collision): each bucket is searched once.
        if (table.offset[b] != table.offset[b + 1] &&
            (b == home || (searchedFrom(table, home, b) && bucketMayHold(table, home, b, reach))) &&
            std::find(around.begin(), around.begin() + count, b) == around.begin() + static_cast<ptrdiff_t>(count))
          around[count++] = b;
      }
  return count;
}

// The pair rule of findContacts (collision.h) for the particles of the table.
struct PartnerRule {
  const Params& p;
  const Topology& topo;
  float frameTime, slack, reach;

  // Appends to `pairs` the pairs (particle, partner) that table entries [first, last), a run of one cell in bucket
  // `home`, list with the particles of buckets around[0 .. count): each pair is listed once, within a bucket by its
  // first entry in the table, between two buckets by the particles of the one whose neighbour is the flatter
  // (searchedFrom, applied by bucketsAround), where the partner radius reads less. A particle farther from a bucket's
  // box than its own reach, or than the partner radius its sheet allows it (partnerRadius), lists nothing there: four
  // entries at a time take these tests, each four read once for all the buckets, the bulk of the search on a film
  // whose buckets are pieces of smooth sheet; the rest search their slab.
  void listRunPartners(const CellTable& table, uint32_t home, const std::array<uint32_t, 27>& around, size_t count,
                       size_t first, size_t last, std::vector<uint32_t>& pairs) const {
    struct Neighbour {  // a bucket around the run: its sheet, and its box in lanes
      const BucketSheet* sheet;
      std::array<Float4, 3> lower, upper;
    };
    std::array<Neighbour, 27> neighbour;
    for (size_t a = 0; a < count; ++a) {
      const BucketSheet& sheet = table.sheet[table.sheetIndex[around[a]]];
      neighbour[a] = {&sheet,
                      {sheet.lower.x(), sheet.lower.y(), sheet.lower.z()},
                      {sheet.upper.x(), sheet.upper.y(), sheet.upper.z()}};
    }
    const Float4 zero(0.0f);
    for (size_t at = first; at < last; at += 4) {
      // The lanes of entries past the run are dropped.
      const auto lanes = [&](const std::vector<float>& axis) { return Float4::load(axis.data() + at); };
      const std::array<Float4, 3> x{lanes(table.x[0]), lanes(table.x[1]), lanes(table.x[2])};
      const std::array<Float4, 3> n{lanes(table.n[0]), lanes(table.n[1]), lanes(table.n[2])};
      const Float4 ownReach = lanes(table.reach);
      const unsigned inRun = last - at >= 4 ? 0xfu : (1u << (last - at)) - 1u;
      for (size_t a = 0; a < count; ++a) {
        const Neighbour& b = neighbour[a];
        Float4 outsideSquared(0.0f);  // from b's box
        for (int axis = 0; axis < 3; ++axis) {
          const Float4 outside = max(max(b.lower[axis] - x[axis], x[axis] - b.upper[axis]), zero);
          outsideSquared = outsideSquared + outside * outside;
        }
        const Float4 radius = widened(min(ownReach, partnerRadius(*b.sheet, x, n)));
        const unsigned tooFar = laneBits(outsideSquared > radius * radius);
        for (unsigned near = inRun & ~tooFar; near; near &= near - 1) {
          const auto l = std::countr_zero(near);
          listPartnersInSlab(table, home, around[a], at + static_cast<size_t>(l), radius.lane(l), pairs);
        }
      }
    }
  }

  // The rest of listRunPartners for table entry `at`: the partners among bucket b's particles within `radius`.
  void listPartnersInSlab(const CellTable& table, uint32_t home, uint32_t b, size_t at, float radius,
                          std::vector<uint32_t>& pairs) const {
    const size_t begin = b == home ? at + 1 : table.offset[b], end = table.offset[b + 1];
    if (begin >= end) return;
    const uint32_t i = table.particle[at];
    const Vec3 xi = table.position[at], ni = table.normal[at];
    const BucketSheet& sheet = table.sheet[table.sheetIndex[b]];
    // |u . d| <= |d| for the unit sort direction u: every partner lies in the slab 2 radius wide about xi. The
    // table's arrays and the rule's figures are read into locals: the appends to `pairs` could otherwise
    // alias them and force a reload per candidate.
    const float* along = table.along.data();
    const Vec3* position = table.position.data();
    const Vec3* normal = table.normal.data();
    const std::array<std::vector<float>, 3>& v = table.v;
    const auto velocity = [&](size_t k) { return Vec3(v[0][k], v[1][k], v[2][k]); };
    const Vec3 vi = velocity(at);
    const float centre = sheet.sortDirection.dot(xi);
    const float reachSquared = reach * reach, distance = p.collisionDistance, time = frameTime, extra = slack;
    // No search where the slab starts before the bucket (always after `at` in its own bucket, and in most buckets
    // of a curved or folded sheet, whose radius is the reach).
    const float lowest = centre - radius, highest = centre + radius;
    const size_t first = along[begin] >= lowest
                             ? begin
                             : static_cast<size_t>(std::lower_bound(along + begin, along + end, lowest) - along);
    // The slab is empty when its first candidate lies past it: on a smooth sheet, whose partner radius is often below
    // the particles' spacing along the sort direction, about a quarter of the searches end here.
    if (first == end || along[first] > highest) return;
    auto consider = [&](size_t k) {
      const Vec3 d = position[k] - xi;
      const float lengthSquared = d.squaredNorm();
      if (!(lengthSquared < reachSquared) || lengthSquared <= 0) return;
      const float pairReach = distance + contactMargin(time, extra, (velocity(k) - vi).norm());
      if (!(lengthSquared < pairReach * pairReach)) return;
      const float alongI = ni.dot(d), alongJ = normal[k].dot(d);
      if (liesAcross(alongI, alongJ, lengthSquared) && !isOneRingNeighbour(topo, i, table.particle[k]))
        pairs.insert(pairs.end(), {i, table.particle[k]});
    };
    size_t k = first;
    // Four candidates at a time from the table's arrays per axis: the same tests as consider()'s, but each a
    // thousandth looser for the order in which the lanes sum, so that consider() alone decides and the list is the
    // one the plain loop makes. Most candidates are the film's own neighbours along the sheet, dropped here
    // without a branch of their own.
    const std::array<Float4, 3> x4{xi.x(), xi.y(), xi.z()}, n4{ni.x(), ni.y(), ni.z()}, v4{vi.x(), vi.y(), vi.z()};
    const Float4 highest4(highest), distance4(distance), time4(time), extra4(extra), cap4(kMaxContactMargin),
        loose(1.001f), acrossLoose(kAcrossCosineSquared * 0.999f);
    auto load = [&](const std::array<std::vector<float>, 3>& axes, int a) { return Float4::load(axes[a].data() + k); };
    for (; k < end; k += 4) {
      const unsigned inBucket = end - k >= 4 ? 0xfu : (1u << (end - k)) - 1u;
      const unsigned inSlab = laneBits(Float4::load(along + k) <= highest4) & inBucket;
      const std::array<Float4, 3> d{load(table.x, 0) - x4[0], load(table.x, 1) - x4[1], load(table.x, 2) - x4[2]};
      const std::array<Float4, 3> w{load(table.v, 0) - v4[0], load(table.v, 1) - v4[1], load(table.v, 2) - v4[2]};
      const Float4 lengthSquared = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      const Float4 closing = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      const Float4 pairReach = distance4 + min(cap4, time4 * closing + extra4);
      const Float4 alongI = n4[0] * d[0] + n4[1] * d[1] + n4[2] * d[2];
      const Float4 alongJ = load(table.n, 0) * d[0] + load(table.n, 1) * d[1] + load(table.n, 2) * d[2];
      const Float4 acrossBound = acrossLoose * lengthSquared;
      const Mask4 candidate = lengthSquared < pairReach * pairReach * loose &&
                              (alongI * alongI > acrossBound || alongJ * alongJ > acrossBound);
      for (unsigned near = laneBits(candidate) & inSlab; near; near &= near - 1)
        consider(k + static_cast<size_t>(std::countr_zero(near)));
      if (inSlab != 0xfu) return;  // the slab or the bucket ends within these four
    }
  }
};

// Each particle's speed about the film's mean velocity into `speed` (0 for a particle not in the film).
void speedsAboutTheMean(const Film& film, std::vector<float>& speed) {
  const State& s = film.state;
  Vec3 sum = Vec3::Zero();
  size_t living = 0;
  for (uint32_t i = 0; i < s.size(); ++i)
    if (inFilm(film, i)) {
      sum += s.velocity.get(i);
      ++living;
    }
  const Vec3 mean = living ? Vec3(sum / static_cast<float>(living)) : Vec3::Zero();
  speed.assign(s.size(), 0.0f);
#pragma omp parallel for schedule(static) if (s.size() >= kParallelPass)
  for (size_t i = 0; i < s.size(); ++i)
    if (inFilm(film, static_cast<uint32_t>(i))) speed[i] = (s.velocity.get(i) - mean).norm();
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
  return contactRestDistanceAfter(p.collisionDistance, previousRest, separation);
}

struct ContactSearch::Memory {
  CellTable table;
  // The pairs (i, j, i, j, ...) each thread listed: one growing array per thread, where one list per particle
  // cost a million empty lists cleared and read each frame on the largest films.
  std::vector<std::vector<uint32_t>> pairsByThread;
  std::vector<float> speed, particleReach;  // find's, per particle
};

ContactSearch::ContactSearch() : memory_(std::make_unique<Memory>()) {}
ContactSearch::~ContactSearch() = default;
ContactSearch::ContactSearch(const ContactSearch&) : ContactSearch() {}
ContactSearch& ContactSearch::operator=(const ContactSearch&) { return *this; }

size_t findContacts(const Params& p, float frameTime, float slack, Film& film, const ContactHistory& history) {
  return ContactSearch().find(p, frameTime, slack, film, history);
}

size_t ContactSearch::find(const Params& p, float frameTime, float slack, Film& film, const ContactHistory& history) {
  const State& s = film.state;
  Topology& topo = film.topology;
  const size_t n = s.size();
  // Two particles close at most by |v_i - v_j| in a frame: a bubble flying as a whole needs no wider search than
  // one at rest, and each pair only its own reach. With |v_i - v_j| <= |v_i - mean| + |v_j - mean|, a particle's
  // partners lie within its own reach, at its speed about the mean plus the fastest one's, and all pairs within the
  // reach at twice the fastest speed, which bounds the cells (cellSizeFor). A slow particle of a film with a fast
  // part searches a narrower slab than the fastest.
  std::vector<float>& speed = memory_->speed;
  speedsAboutTheMean(film, speed);
  const float fastest = n ? *std::max_element(speed.begin(), speed.end()) : 0.0f;
  const float reach = p.collisionDistance + contactMargin(frameTime, slack, 2.0f * fastest);
  std::vector<float>& particleReach = memory_->particleReach;
  particleReach.resize(n);
  std::transform(speed.begin(), speed.end(), particleReach.begin(),
                 [&](float v) { return p.collisionDistance + contactMargin(frameTime, slack, v + fastest); });
  std::vector<std::vector<uint32_t>>& pairsByThread = memory_->pairsByThread;
  pairsByThread.resize(static_cast<size_t>(std::max(omp_get_max_threads(), 1)));
  for (std::vector<uint32_t>& pairs : pairsByThread) pairs.clear();
  if (reach > 0 && p.collisionStiffness > 0) {
    const FilmExtent extent = extentOf(film);
    const float cellSize = cellSizeFor(extent, reach);
    bucketParticles(film, particleReach, extent, cellSize, memory_->table);
    const CellTable& table = memory_->table;
    const PartnerRule rule{p, topo, frameTime, slack, reach};
    // Each particle lists the partners it owns (each pair once, half the distance tests; listRunPartners) from the
    // read-only table: parallel over the buckets, each thread into its own array, and the same rows in any order
    // once they are sorted below. The particles of a cell share the buckets about it, looked up once per run of
    // particles of one cell.
#pragma omp parallel
    {
      std::vector<uint32_t>& pairs = pairsByThread[static_cast<size_t>(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1)
      for (size_t o = 0; o < table.occupied.size(); ++o) {
        const uint32_t b = table.occupied[o];
        std::array<uint32_t, 27> around{};
        for (size_t first = table.offset[b], last = first; first < table.offset[b + 1]; first = last) {
          const Cell cell = cellOf(table.position[first], cellSize);
          while (++last < table.offset[b + 1] && cellOf(table.position[last], cellSize) == cell) {
          }
          const size_t count = bucketsAround(table, b, cell, reach, around);
          rule.listRunPartners(table, b, around, count, first, last, pairs);
        }
      }
    }
  }
  // Each pair was listed once: each particle's row holds the partners it listed and those that listed it, sorted.
  std::vector<uint32_t> packed(n + 1, 0u);
  for (const std::vector<uint32_t>& pairs : pairsByThread)
    for (uint32_t end : pairs) ++packed[end + 1];
  for (size_t i = 0; i < n; ++i) packed[i + 1] += packed[i];
  const size_t total = packed[n];
  packed.resize(n + 1 + 2 * total);
  std::vector<uint32_t> fill(packed.begin(), packed.begin() + static_cast<ptrdiff_t>(n));
  for (const std::vector<uint32_t>& pairs : pairsByThread)
    for (size_t k = 0; k < pairs.size(); k += 2) {
      const uint32_t i = pairs[k], j = pairs[k + 1];
      packed[n + 1 + fill[i]++] = j;
      packed[n + 1 + fill[j]++] = i;
    }
  auto row = [&](size_t i) { return packed.begin() + static_cast<ptrdiff_t>(n + 1 + packed[i]); };
#pragma omp parallel for schedule(dynamic, 256)
  for (uint32_t i = 0; i < n; ++i) {
    std::sort(row(i), row(i + 1));
    for (uint32_t k = packed[i]; k < packed[i + 1]; ++k) {
      const uint32_t j = packed[n + 1 + k];
      const float separation = (s.position.get(i) - s.position.get(j)).norm();
      const float rest = contactRestDistanceAfter(p, previousRestDistance(history, i, j), separation);
      packed[n + 1 + total + k] = std::bit_cast<uint32_t>(rest);
    }
  }
  topo.contacts = std::move(packed);
  return total / 2;
}

float impactNumber(const Params& params, float approachSpeed, float elasticity) {
  return impactNumberOf(params.filmInertia, approachSpeed, elasticity);
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

bool insideClosedFilm(const Film& film, const Vec3& x) {
  const State& s = film.state;
  Vec3 lower = Vec3::Constant(std::numeric_limits<float>::infinity()), upper = -lower;
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i]) lower = lower.cwiseMin(s.position.get(i)), upper = upper.cwiseMax(s.position.get(i));
  if ((x.array() < lower.array()).any() || (x.array() > upper.array()).any()) return false;
  return windingNumber(film, x) > 0.5;
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
