// Film growth at the wire: stretch test, ring release, new ring on the wire, CGAL strip triangulation.
// CGAL stays inside this file.
#include "topology/film_growth.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>

#include "solver/implicit_euler.h"
#include "topology/pinch_off.h"

namespace gb {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;

// Distance along the wire from u = 0 to frame coordinate u, exact on the straight top string and
// proportional to the angle on the arcs: the strip's flat coordinate, only used to pick its triangles.
struct WireUnrolling {
  const WireFrame& frame;
  float topLength = 0.0f, arcLength = 0.0f;
  explicit WireUnrolling(const WireFrame& f) : frame(f) {
    if (f.kind == ToolKind::TwoWands) {
      topLength = 2.0f * f.halfWidth;
      arcLength = frameArcLength(f, 1.0f, 2.0f);
    } else {
      arcLength = frameArcLength(f, 0.0f, 1.0f);
    }
  }
  [[nodiscard]] float at(float u) const {
    if (frame.kind == ToolKind::Ring) return u * arcLength;
    return u < 1.0f ? u * topLength : topLength + (u - 1.0f) * arcLength;
  }
  [[nodiscard]] float period() const { return topLength + arcLength; }
};

// The wire's particles and, for each, the springs to free particles of the film.
bool isRung(const Topology& topo, uint32_t a, uint32_t b) { return topo.boundary[a] && !topo.boundary[b]; }

// Where a released wire particle goes: `fraction` of the way to the mean of its free neighbours; a particle
// with no free neighbour (a sharp tip) steps that fraction of the wire spacing towards the frame's centre.
Vec3 releasedPosition(const Film& film, const WireFrame& frame, uint32_t i, float fraction) {
  const Topology& topo = film.topology;
  const State& s = film.state;
  Vec3 mean = Vec3::Zero();
  int count = 0;
  for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k)
    if (const uint32_t j = topo.springNeighbour[k]; isRung(topo, i, j)) {
      mean += s.position.get(j);
      ++count;
    }
  const Vec3 p = s.position.get(i);
  if (count > 0) return p + fraction * (mean / static_cast<float>(count) - p);
  const Vec3 towardsCentre = (frame.center - p).normalized();
  return p + fraction * film.wireSpacing * towardsCentre;
}

// Triangles of the strip between the released ring (old, at height 1) and the new ring (at height 0),
// unrolled along the wire, by CGAL's Delaunay triangulation. The unrolled strip is closed into an annulus
// by a copy of each ring's first point one period further on, mapped back to the same particle.
std::vector<uint32_t> triangulateStrip(const WireUnrolling& wire, const std::vector<uint32_t>& oldRing,
                                       const std::vector<float>& oldU, const std::vector<uint32_t>& newRing,
                                       const std::vector<float>& newU, float height) {
  std::vector<std::pair<Kernel::Point_2, uint32_t>> points;
  auto addRing = [&](const std::vector<uint32_t>& ring, const std::vector<float>& us, float y) {
    size_t first = 0;
    for (size_t k = 0; k < ring.size(); ++k) {
      points.emplace_back(Kernel::Point_2(wire.at(us[k]), y), ring[k]);
      if (us[k] < us[first]) first = k;
    }
    points.emplace_back(Kernel::Point_2(wire.at(us[first]) + wire.period(), y), ring[first]);
  };
  addRing(oldRing, oldU, height);
  addRing(newRing, newU, 0.0f);
  const Delaunay strip(points.begin(), points.end());
  std::vector<uint32_t> triangles;
  for (auto f = strip.finite_faces_begin(); f != strip.finite_faces_end(); ++f) {
    const uint32_t a = f->vertex(0)->info(), b = f->vertex(1)->info(), c = f->vertex(2)->info();
    if (a == b || b == c || c == a) continue;  // spans the whole period: its copy is the real one
    triangles.insert(triangles.end(), {a, b, c});
  }
  return triangles;
}

// The released ring's springs to the film were stretched past growthStretch and are now half as long: the
// film there has been drawn out of the wire, so they rest as a new film's springs do, prestrained at their
// current length (the wire's payout of new film relaxes the tension it had).
void restLikeNewFilm(const Params& params, const std::vector<uint32_t>& released, Film& film) {
  Topology& topo = film.topology;
  std::vector<char> isReleased(film.state.size(), 0);
  for (uint32_t i : released) isReleased[i] = 1;
  for (uint32_t a : released)  // each such spring from its released end
    for (uint32_t k = topo.springOffset[a]; k < topo.springOffset[a + 1]; ++k)
      if (const uint32_t b = topo.springNeighbour[k]; !isReleased[b] && !topo.boundary[b])
        topo.restLength[topo.springIndex[k]] =
            (film.state.position.get(a) - film.state.position.get(b)).norm() * (1.0f - params.springPrestrain);
}

// The strip's liquid, a new film's thickness times its area, shared among the corners of its triangles (a
// third of each triangle to each): the new particles get their share, the released ring adds its share to
// what it had. A wire with less liquid than that gives what it has (the last strip is thinner). Returns the
// liquid used. Inertia is per area (Params::filmInertia), so the strip's particles get the mass of their new
// Voronoi areas: a released ring particle now has film on both sides, and keeping its half-area wire mass
// would halve the stable time step.
float shareStripMaterial(const Params& params, const std::vector<uint32_t>& strip, size_t first, float available,
                         State& s) {
  std::vector<float> cornerArea(strip.size() / 3);
  double area = 0;
  for (size_t t = 0; t < strip.size(); t += 3) {
    const Vec3 a = s.position.get(strip[t]), b = s.position.get(strip[t + 1]), c = s.position.get(strip[t + 2]);
    cornerArea[t / 3] = 0.5f * (b - a).cross(c - a).norm() / 3.0f;
    area += 3.0 * cornerArea[t / 3];
  }
  const float wanted = static_cast<float>(initialThickness(params) * area);
  const float used = std::min(wanted, available);
  const float thickness = area > 0 ? static_cast<float>(used / area) : 0.0f;
  for (size_t i = first; i < s.size(); ++i) s.liquid[i] = 0.0f;
  for (size_t t = 0; t < strip.size(); t += 3)
    for (size_t k = 0; k < 3; ++k) s.liquid[strip[t + k]] += thickness * cornerArea[t / 3];
  for (uint32_t i : strip) s.mass[i] = particleMass(params, s.voronoiArea[i], s.liquid[i]);
  return used;
}

// The band the payout drew off the wire since the last ring (payOutFilmAtWire lengthens rest lengths alone, so the
// band widens without liquid): the released ring and the film's particles joined to it, whose Voronoi areas take the
// band's two halves. A fast stroke widens the band by several spacings a frame; a ring and its neighbours then hold a
// narrow strip's liquid over a wide band and thin a hundredfold within a few frames (real hands, docs/capture.md).
std::vector<uint32_t> bandOf(const Topology& topo, const std::vector<uint32_t>& released) {
  std::vector<char> in(topo.boundary.size(), 0);
  std::vector<uint32_t> band = released;
  for (uint32_t i : released) in[i] = 1;
  for (uint32_t i : released)
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k)
      if (const uint32_t j = topo.springNeighbour[k]; !in[j] && !topo.boundary[j]) {
        in[j] = 1;
        band.push_back(j);
      }
  return band;
}

// The band's liquid comes from the wire too: each of its particles is brought up to a new film's thickness over its
// Voronoi area where it is thinner, as far as the wire's `available` liquid goes (shared in proportion where it does
// not). Returns the liquid used.
float feedBandFromWire(const Params& params, const std::vector<uint32_t>& band, float available, State& s) {
  const float dipThickness = initialThickness(params);
  auto wanted = [&](uint32_t i) { return std::max(0.0f, dipThickness * s.voronoiArea[i] - s.liquid[i]); };
  double total = 0;
  for (uint32_t i : band) total += wanted(i);
  if (!(total > 0) || !(available > 0)) return 0.0f;
  const auto share = static_cast<float>(std::min(1.0, available / total));
  for (uint32_t i : band) {
    s.liquid[i] += share * wanted(i);
    s.mass[i] = particleMass(params, s.voronoiArea[i], s.liquid[i]);
  }
  return static_cast<float>(std::min<double>(available, total));
}

// The film's single boundary loop, or empty when it has none or several (a torn or closed film).
std::vector<uint32_t> intactWireLoop(const Film& film) {
  if (film.topology.isClosed()) return {};
  for (uint32_t a : film.state.alive)
    if (!a) return {};
  try {
    return boundaryLoop(film.topology);
  } catch (const std::runtime_error&) {
    return {};
  }
}

}  // namespace

float wireRungStretch(const Film& film) {
  const Topology& topo = film.topology;
  const State& s = film.state;
  double sum = 0;
  size_t count = 0;
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    if (!isRung(topo, a, b) && !isRung(topo, b, a)) continue;
    if (!s.alive[a] || !s.alive[b] || topo.restLength[k] <= 0) continue;
    sum += (s.position.get(a) - s.position.get(b)).norm() / topo.restLength[k];
    ++count;
  }
  return count ? static_cast<float>(sum / static_cast<double>(count)) : 0.0f;
}

size_t payOutFilmAtWire(const Params& params, Film& film) {
  if (film.wireLiquid <= 0.0f) return 0;
  Topology& topo = film.topology;
  const State& s = film.state;
  std::vector<std::pair<size_t, float>> stretched;  // rung, its length
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    if (!isRung(topo, a, b) && !isRung(topo, b, a)) continue;
    const float length = (s.position.get(a) - s.position.get(b)).norm();
    if (rungPaysOut(length, topo.restLength[k], params.growthStretch)) stretched.emplace_back(k, length);
  }
  // The loop test walks every triangle's edges: only when there is something to pay out (every frame the wands
  // move, otherwise).
  if (stretched.empty() || intactWireLoop(film).empty()) return 0;
  for (const auto& [k, length] : stretched)
    topo.restLength[k] = length * (1.0f - params.springPrestrain);  // as taut as a new film, no more
  return stretched.size();
}

namespace {

// Passes over the springs run in parallel only on films with this many: on a small film the threads' start and join
// cost more than the pass.
constexpr long kParallelSprings = long{1} << 16;

// Whether the spring between a and b lives and is not held by the wire (the wire's springs follow the wire's own
// rule, payOutFilmAtWire, which also decides ring insertion).
bool livesOffTheWire(const Film& film, uint32_t a, uint32_t b) {
  const State& s = film.state;
  const Topology& topo = film.topology;
  return s.alive[a] && s.alive[b] && !topo.boundary[a] && !topo.boundary[b];
}

// Calls body(spring, its ends, its length) for every living spring not held by the wire.
template <typename Body>
void forEachSpringOffTheWire(const Film& film, Body body) {
  const Topology& topo = film.topology;
  const State& s = film.state;
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    if (!livesOffTheWire(film, a, b)) continue;
    body(k, a, b, (s.position.get(a) - s.position.get(b)).norm());
  }
}

// Gives every living spring not held by the wire the rest length newRest(spring, its ends, its length) returns,
// where it returns one. Returns how many changed. In parallel over the springs: newRest reads what no spring writes
// but its own rest length, so the result is the serial loop's. It runs every frame on every spring (3 million on a
// film of a million particles).
template <typename NewRest>
size_t reshapeSpringsOffTheWire(Film& film, NewRest newRest) {
  Topology& topo = film.topology;
  const State& s = film.state;
  const auto springs = static_cast<long>(topo.springCount());
  size_t changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed) if (springs >= kParallelSprings)
  for (long spring = 0; spring < springs; ++spring) {
    const auto k = static_cast<size_t>(spring);
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    if (!livesOffTheWire(film, a, b)) continue;
    const std::optional<float> rest = newRest(k, a, b, (s.position.get(a) - s.position.get(b)).norm());
    if (!rest) continue;
    topo.restLength[k] = *rest;
    ++changed;
  }
  return changed;
}

}  // namespace

size_t contractSlackSprings(const Params& params, Film& film) {
  SpringEnergyAllowance unbounded;
  return contractSlackSprings(params, film, unbounded);
}

ContractionEnergy contractionEnergy(const Params& params, const Film& film) {
  if (params.tensionModel != 0) return {};
  const std::vector<float>& rest = film.topology.restLength;
  const State& s = film.state;
  const float dipThickness = initialThickness(params);
  double quadratic = 0.0, linear = 0.0;
  forEachSpringOffTheWire(film, [&](size_t k, uint32_t a, uint32_t b, float length) {
    if (!springContracts(length, rest[k], std::max(s.thickness[a], s.thickness[b]), dipThickness)) return;
    const float taut = tautRestLengthOf(length, rest[k], params.springPrestrain, params.energyNeutralContraction);
    const float stiffness = springStiffness(s, a, b);
    quadratic += contractionQuadraticOf(stiffness, rest[k], taut);
    linear += contractionLinearOf(stiffness, length, rest[k], taut);
  });
  return {static_cast<float>(quadratic), static_cast<float>(linear)};
}

size_t contractSlackSprings(const Params& params, Film& film, SpringEnergyAllowance& allowance) {
  // The physical model's tension does not use rest lengths (tensionModel 1).
  if (params.tensionModel != 0) return 0;
  const ContractionEnergy energy = contractionEnergy(params, film);
  const float share = contractionShareOf(energy.quadratic, energy.linear, allowance.joules);
  if (share == 0.0f) return 0;
  allowance.joules -= contractionEnergyOf(share, energy.quadratic, energy.linear);
  const std::vector<float>& rest = film.topology.restLength;
  const std::vector<float>& thickness = film.state.thickness;
  const float dipThickness = initialThickness(params);
  return reshapeSpringsOffTheWire(film, [&](size_t k, uint32_t a, uint32_t b, float length) -> std::optional<float> {
    if (!springContracts(length, rest[k], std::max(thickness[a], thickness[b]), dipThickness)) return std::nullopt;
    const float taut = tautRestLengthOf(length, rest[k], params.springPrestrain, params.energyNeutralContraction);
    return contractedRestLengthOf(rest[k], taut, share);
  });
}

namespace {

// The particles around i (its one-ring).
std::span<const uint32_t> ringOf(const Topology& topo, uint32_t i) {
  return {topo.springNeighbour.data() + topo.springOffset[i], topo.springOffset[i + 1] - topo.springOffset[i]};
}

// Whether merging b into a at x keeps the mesh a manifold that does not fold over: the two one-rings share exactly
// the two particles across the edge (the link condition), and no triangle that keeps one of them turns over.
bool mergeKeepsTheMesh(const Film& film, uint32_t a, uint32_t b, const Vec3& x) {
  const Topology& topo = film.topology;
  const State& s = film.state;
  size_t shared = 0;
  for (uint32_t n : ringOf(topo, a))
    for (uint32_t m : ringOf(topo, b)) shared += n == m;
  if (shared != 2) return false;
  for (uint32_t moved : {a, b})
    for (uint32_t k = topo.triangleOffset[moved]; k < topo.triangleOffset[moved + 1]; ++k) {
      const uint32_t* tri = topo.triangleOf(topo.triangleCorner[k]);
      if ((tri[0] == a || tri[1] == a || tri[2] == a) && (tri[0] == b || tri[1] == b || tri[2] == b)) continue;
      std::array<Vec3, 3> before, after;
      for (int c = 0; c < 3; ++c) {
        before[c] = s.position.get(tri[c]);
        after[c] = tri[c] == moved ? x : before[c];
      }
      const Vec3 n0 = (before[1] - before[0]).cross(before[2] - before[0]);
      const Vec3 n1 = (after[1] - after[0]).cross(after[2] - after[0]);
      if (!(n0.dot(n1) > 0.5f * n0.norm() * n1.norm())) return false;  // turned by more than 60 degrees
    }
  return true;
}

// Particle b joins particle a at their centre of mass: its mass, liquid and momentum go to a, and b dies; the film
// flow's surfactant per liquid and liquid velocity become their liquid-weighted means.
void mergeInto(State& s, uint32_t a, uint32_t b) {
  const float ma = s.mass[a], mb = s.mass[b], m = ma + mb;
  if (const float la = s.liquid[a], lb = s.liquid[b]; la + lb > 0.0f) {
    s.surfactant[a] = (la * s.surfactant[a] + lb * s.surfactant[b]) / (la + lb);
    s.flowVelocity.set(a, (la * s.flowVelocity.get(a) + lb * s.flowVelocity.get(b)) / (la + lb));
  }
  s.position.set(a, (ma * s.position.get(a) + mb * s.position.get(b)) / m);
  s.previousPosition.set(a, (ma * s.previousPosition.get(a) + mb * s.previousPosition.get(b)) / m);
  s.velocity.set(a, (ma * s.velocity.get(a) + mb * s.velocity.get(b)) / m);
  s.mass[a] = m;
  s.liquid[a] += s.liquid[b];
  s.lifetime[a] = std::min(s.lifetime[a], s.lifetime[b]);
  s.alive[b] = 0u;
  s.liquid[b] = 0.0f;
  s.mass[b] = 0.0f;
}

}  // namespace

size_t mergeCrowdedParticles(const Params& params, Film& film) {
  SpringEnergyAllowance unbounded;
  return mergeCrowdedParticles(params, film, unbounded);
}

size_t mergeCrowdedParticles(const Params& params, Film& film, SpringEnergyAllowance& allowance) {
  if (!film.topology.isClosed() || params.tensionModel != 0 || film.topology.springCount() == 0) return 0;
  std::vector<CrowdedSpring> crowded = crowdedSprings(params, film);
  if (crowded.empty()) return 0;  // most frames: the median is not needed
  keepTheMergeable(crowded, medianSpringLength(film));
  const std::vector<Merge> merges = chooseMerges(film, crowded);
  if (!merges.empty()) makeMerges(params, film, merges, allowance);
  return merges.size();
}

float springLength(const State& s, uint32_t a, uint32_t b) {
  return std::sqrt(squaredLengthOf(s.position.x[a] - s.position.x[b], s.position.y[a] - s.position.y[b],
                                   s.position.z[a] - s.position.z[b]));
}

float medianSpringLength(const Film& film) {
  const Topology& topo = film.topology;
  const State& s = film.state;
  std::vector<float> lengths;
  lengths.reserve(topo.springCount());
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    if (s.alive[a] && s.alive[b]) lengths.push_back(springLength(s, a, b));
  }
  if (lengths.empty()) return 0.0f;
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  return lengths[lengths.size() / 2];
}

namespace {

// Spring k with its length, where it lives and is crowded.
std::optional<CrowdedSpring> crowdedSpring(const Params& params, const Film& film, size_t k) {
  const Topology& topo = film.topology;
  const State& s = film.state;
  const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
  if (!s.alive[a] || !s.alive[b]) return std::nullopt;
  const float length = springLength(s, a, b);
  if (!springCrowded(length, topo.restLength[k], std::max(s.thickness[a], s.thickness[b]), initialThickness(params)))
    return std::nullopt;
  return CrowdedSpring{length, k};
}

}  // namespace

std::vector<CrowdedSpring> crowdedSprings(const Params& params, const Film& film) {
  std::vector<CrowdedSpring> crowded;
  for (size_t k = 0; k < film.topology.springCount(); ++k)
    if (const std::optional<CrowdedSpring> c = crowdedSpring(params, film, k)) crowded.push_back(*c);
  return crowded;
}

std::vector<CrowdedSpring> crowdedSpringsAmong(const Params& params, const Film& film,
                                               std::span<const uint32_t> springs) {
  std::vector<CrowdedSpring> crowded;
  for (uint32_t k : springs)
    if (const std::optional<CrowdedSpring> c = crowdedSpring(params, film, k)) crowded.push_back(*c);
  return crowded;
}

void keepTheMergeable(std::vector<CrowdedSpring>& crowded, float medianLength) {
  const float shortest = kCrowdedEdge * medianLength;
  std::erase_if(crowded, [&](const CrowdedSpring& c) { return !(c.length < shortest); });
  std::sort(crowded.begin(), crowded.end());
}

std::vector<Merge> chooseMerges(const Film& film, const std::vector<CrowdedSpring>& tried) {
  const Topology& topo = film.topology;
  const State& s = film.state;
  // Merged or beside a merge this round: its ring changes. A merge leaves the positions that a later one reads
  // as they were (those of its one-rings, which no merge before it touched), so the merges are chosen first.
  std::vector<char> touched(s.size(), 0);
  std::vector<Merge> merges;
  for (const CrowdedSpring& c : tried) {
    const uint32_t a = topo.springEnds[2 * c.spring], b = topo.springEnds[2 * c.spring + 1];
    if (touched[a] || touched[b]) continue;
    const float ma = s.mass[a], mb = s.mass[b];
    const Vec3 x = (ma * s.position.get(a) + mb * s.position.get(b)) / (ma + mb);
    if (!mergeKeepsTheMesh(film, a, b, x)) continue;
    for (uint32_t p : {a, b}) {
      touched[p] = 1;
      for (uint32_t n : ringOf(topo, p)) touched[n] = 1;
    }
    merges.push_back({a, b});
  }
  return merges;
}

void makeMerges(const Params& params, Film& film, const std::vector<Merge>& merges, SpringEnergyAllowance& allowance,
                std::vector<uint32_t>* from) {
  Topology& topo = film.topology;
  State& s = film.state;
  std::vector<uint32_t> into(s.size());
  for (uint32_t i = 0; i < into.size(); ++i) into[i] = i;
  for (const Merge& m : merges) {
    mergeInto(s, m.survivor, m.joining);
    into[m.joining] = m.survivor;
  }
  std::vector<uint32_t> triangles;
  triangles.reserve(topo.triangles.size());
  for (size_t t = 0; t < topo.triangleCount(); ++t) {
    const std::array<uint32_t, 3> tri{into[topo.triangles[3 * t]], into[topo.triangles[3 * t + 1]],
                                      into[topo.triangles[3 * t + 2]]};
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;  // the two across each merged edge
    triangles.insert(triangles.end(), tri.begin(), tri.end());
  }
  std::vector<uint32_t> springFrom;
  topo =
      collapsedTopology(std::move(topo), std::move(triangles), into, s.position, params.springPrestrain, &springFrom);
  for (size_t k = 0; k < springFrom.size();
       ++k) {  // as taut as new film while the allowance pays, else at their length
    if (springFrom[k] != kMadeSpring) continue;
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    const float length = (s.position.get(a) - s.position.get(b)).norm();
    if (!allowance.pays(springEnergy(s, a, b, length, topo.restLength[k]))) topo.restLength[k] = length;
  }
  if (from) *from = std::move(springFrom);
}

size_t yieldStretchedSprings(const Params& params, Film& film) {
  if (!(params.yieldStretch > 1.0f) || params.tensionModel != 0) return 0;
  const std::vector<float>& rest = film.topology.restLength;
  const std::vector<float>& thickness = film.state.thickness;
  return reshapeSpringsOffTheWire(film, [&](size_t k, uint32_t a, uint32_t b, float length) -> std::optional<float> {
    if (!springYields(length, rest[k], std::min(thickness[a], thickness[b]), params.yieldStretch,
                      params.yieldThickness))
      return std::nullopt;
    return length / params.yieldStretch;
  });
}

float wireBandWidth(const Film& film) {
  const Topology& topo = film.topology;
  double rungRest = 0, edgeLength = 0;
  size_t rungs = 0, edges = 0;
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    if (isRung(topo, a, b) || isRung(topo, b, a)) {
      rungRest += topo.restLength[k];
      ++rungs;
    } else if (topo.boundary[a] && topo.boundary[b]) {
      edgeLength += (film.state.position.get(a) - film.state.position.get(b)).norm();
      ++edges;
    }
  }
  return wireBandWidthOf(rungRest, static_cast<double>(rungs), edgeLength, static_cast<double>(edges));
}

float wireBandWidthOf(double rungRest, double rungs, double edgeLength, double edges) {
  if (rungs <= 0 || edges <= 0 || edgeLength <= 0) return 0.0f;
  return static_cast<float>((rungRest / rungs) / (edgeLength / edges));
}

bool wireLoopIntact(const Film& film) { return !intactWireLoop(film).empty(); }

FilmRegion wireGrowthRegion(const Film& film) {
  const Topology& topo = film.topology;
  std::vector<char> in(topo.boundary.size(), 0);
  std::vector<uint32_t> ring;  // the particles the last pass added
  FilmRegion region;
  for (uint32_t i = 0; i < topo.boundary.size(); ++i)
    if (topo.boundary[i]) {
      in[i] = 1;
      ring.push_back(i);
      for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k)
        region.springs.push_back(topo.springIndex[k]);
    }
  for (int pass = 0; pass < 2; ++pass) {  // the band joined to the wire's ring, and the ring around the band
    std::vector<uint32_t> next;
    for (uint32_t i : ring)
      for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k)
        if (const uint32_t j = topo.springNeighbour[k]; !in[j]) {
          in[j] = 1;
          next.push_back(j);
        }
    ring = std::move(next);
  }
  for (uint32_t i = 0; i < in.size(); ++i)
    if (in[i]) region.particles.push_back(i);
  std::sort(region.springs.begin(), region.springs.end());
  region.springs.erase(std::unique(region.springs.begin(), region.springs.end()), region.springs.end());
  return region;
}

GrowthEvent growFilmAtWire(const Params& params, const WireFrame& frame, float wandSpeed, Film& film, bool payOut) {
  GrowthEvent event;
  if (payOut && wandSpeed >= kDrawingSpeed) event.restLengthsChanged = payOutFilmAtWire(params, film);
  if (wireBandWidth(film) < kRingInsertionWidth || film.tool.kind != frame.kind) return event;
  const std::vector<uint32_t> loop = intactWireLoop(film);
  if (loop.size() < 3 || film.wireLiquid <= 0.0f) return event;

  // The new ring's spacing is that of a dip with the solution now left (particle count ~ solution), at most
  // twice the dip's: a nearly dry wire still draws a strip the mesh can resolve.
  const float solution = std::max(film.solutionLeft(params), 1e-6f);
  const float spacing = film.wireSpacing * std::min(2.0f, std::sqrt(params.solution / solution));
  const std::vector<float> newU = wireParameters(frame, spacing);

  // The film grows in place (copying it cost as much as the rest at 100,000 particles); until its mesh has taken the
  // strip, what changed in the state is undone where that fails.
  State& s = film.state;
  const size_t first = s.size();
  constexpr float fraction = 0.5f;  // halfway: the two bands come out alike, about 0.8 spacing wide
  std::vector<float> oldU;
  std::vector<Vec3> held, released;
  for (uint32_t i : loop) {
    oldU.push_back(s.wireParam[i]);
    held.push_back(s.position.get(i));
    released.push_back(releasedPosition(film, frame, i, fraction));
  }
  for (size_t k = 0; k < loop.size(); ++k) s.position.set(loop[k], released[k]);
  s.append(newU.size());
  std::vector<uint32_t> newRing;
  for (size_t k = 0; k < newU.size(); ++k) {
    const auto i = static_cast<uint32_t>(first + k);
    newRing.push_back(i);
    s.position.set(i, wirePoint(frame, newU[k]));
    s.wireParam[i] = newU[k];
  }

  std::vector<uint32_t> strip = triangulateStrip(WireUnrolling(frame), loop, oldU, newRing, newU, spacing);
  orientAgainstLoop(loop, strip);
  try {
    appendTriangles(film.topology, s.size(), strip, s.position, params.springPrestrain);
  } catch (...) {
    s.removeFrom(first);
    for (size_t k = 0; k < loop.size(); ++k) s.position.set(loop[k], held[k]);
    throw;
  }
  event.trianglesAdded = strip.size() / 3;
  restLikeNewFilm(params, loop, film);
  if (intactWireLoop(film).size() != newRing.size())
    throw std::logic_error("film growth: the new strip does not leave the new ring as the film's only edge");
  // The strip's particles and the band inside it: the geometry changed around them alone.
  const std::vector<uint32_t> band = bandOf(film.topology, loop);
  std::vector<uint32_t> around = band;
  around.insert(around.end(), newRing.begin(), newRing.end());
  computeGeometryAround(film.topology, s, around);
  giveNewFilmMaterial(params, s, first);
  const float stripLiquid = shareStripMaterial(params, strip, first, film.wireLiquid, s);
  film.wireLiquid = std::max(0.0f, film.wireLiquid - stripLiquid);
  const float bandLiquid = feedBandFromWire(params, band, film.wireLiquid, s);
  film.wireLiquid = std::max(0.0f, film.wireLiquid - bandLiquid);
  event.liquidUsed = stripLiquid + bandLiquid;
  event.particlesAdded = newRing.size();
  return event;
}

}  // namespace gb
