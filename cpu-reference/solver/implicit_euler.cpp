#include "solver/implicit_euler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "solver/energy_budget.h"
#include "solver/particle_lanes.h"

namespace gb {

namespace {

// The block's terms are written once, as templates on the float type F (float_lanes.h): float sums one
// particle's block (objectiveBlock), Float4 four particles' of one colour in the lanes of a register
// (vertexBlockDescentRun, the CPU stepper's sweeps). A lane's terms are the float ones operation for operation; a
// term a lane does not have (a shorter one-ring, a degenerate spring or triangle, a contact out of range) adds
// +0 there.
template <class F>
using Vec = Vec3Of<F>;
template <class F>
using Particles = std::array<uint32_t, kLanes<F>>;  // the particle of each lane

// A block while its terms are summed: the symmetric Hessian as its six distinct entries in locals, so that the
// sum stays in registers. (Summing 3x3 matrices built per term goes through the stack, and reading those
// temporaries back costs more than the sweep's arithmetic.) Entry (r, c) gets
// scale (d_r d_c) per term, the same float operations as an outer-product matrix, so the sum equals the
// matrix sum bit for bit.
template <class F>
struct BlockSum {
  Vec<F> gradient{F(0.0f), F(0.0f), F(0.0f)};
  F xx = F(0.0f), xy = F(0.0f), xz = F(0.0f), yy = F(0.0f), yz = F(0.0f), zz = F(0.0f);
  F shortestSpring = F(std::numeric_limits<float>::infinity());

  // gradient += g in the lanes of m
  void addGradient(MaskOf<F> m, const Vec<F>& g) { gradient = gradient + masked(m, g); }
  void subtractGradient(MaskOf<F> m, const Vec<F>& g) { gradient = gradient - masked(m, g); }
  // hessian += scale d d^T in the lanes of m
  void addOuter(MaskOf<F> m, F scale, const Vec<F>& d) {
    xx = xx + masked(m, scale * (d.x * d.x));
    xy = xy + masked(m, scale * (d.x * d.y));
    xz = xz + masked(m, scale * (d.x * d.z));
    yy = yy + masked(m, scale * (d.y * d.y));
    yz = yz + masked(m, scale * (d.y * d.z));
    zz = zz + masked(m, scale * (d.z * d.z));
  }
  // hessian += scale I
  void addIsotropic(F scale) {
    xx = xx + scale;
    yy = yy + scale;
    zz = zz + scale;
  }
};

VertexBlock blockOf(const BlockSum<float>& b) {
  VertexBlock v;
  v.gradient = eigenOf(b.gradient);
  v.hessian << b.xx, b.xy, b.xz, b.xy, b.yy, b.yz, b.xz, b.yz, b.zz;
  v.shortestSpring = b.shortestSpring;
  return v;
}

// Damping along a direction, dissipation c/(2h) ((dx_i - dx_j) . dir)^2 with dx the displacement over the
// step: the implicit form of the damping force c ((v_j - v_i) . dir) dir. Its Hessian c/h dir dir^T is
// returned for the caller to add with the other terms along dir.
template <class F>
F addDampingGradient(MaskOf<F> m, F coefficient, F h, const Vec<F>& dir, const Vec<F>& relativeDisplacement,
                     BlockSum<F>& b) {
  b.addGradient(m, (coefficient / h * dot(relativeDisplacement, dir)) * dir);
  return coefficient / h;
}

// triangleTensionAt (implicit_euler.h) and its slope dT/dA: E_G / A, or 0 where the tension is clamped or the
// law does not apply (no Gibbs elasticity, or a degenerate triangle: the tension it started with).
template <class F>
struct TriangleTension {
  F tension, slope;
};
template <class F>
TriangleTension<F> triangleTensionOf(const Params& p, F startTension, F startArea, F area) {
  const F gibbs(p.gibbsElasticity), lowest(lowestTension(p.surfaceTension)), highest(highestTension(p.surfaceTension));
  const MaskOf<F> follows = F(0.0f) < gibbs && F(0.0f) < startArea && F(0.0f) < area;
  const F unclamped = startTension + gibbs * logOf(select(follows, area / startArea, F(1.0f)));
  const MaskOf<F> elastic = follows && lowest < unclamped && unclamped < highest;
  return {select(follows, min(max(unclamped, lowest), highest), startTension), select(elastic, gibbs / area, F(0.0f))};
}

// Physical model: the tension energy of triangle (x, xj, xl), counter-clockwise, that had startArea and
// startTension where the step started (triangleTensionEnergy). grad_x A = 1/2 n x (xl - xj); the Hessian of A in
// x alone is |xl - xj|^2 / (4 A) n n^T, positive semi-definite, and the Gibbs law adds dT/dA grad A grad A^T: the
// film's only stiffness in its own plane in this model.
template <class F>
void addAreaTension(const Params& p, MaskOf<F> live, F startTension, F startArea, const Vec<F>& x, const Vec<F>& xj,
                    const Vec<F>& xl, BlockSum<F>& b) {
  const Vec<F> twiceAreaNormal = cross(xj - x, xl - x);
  const F twiceArea = norm(twiceAreaNormal);
  const MaskOf<F> m = live && twiceArea > F(0.0f);
  if (none(m)) return;
  const Vec<F> n = twiceAreaNormal / twiceArea;
  const Vec<F> edge = xl - xj;
  const TriangleTension<F> t = triangleTensionOf(p, startTension, startArea, F(0.5f) * twiceArea);
  const Vec<F> areaGradient = F(0.5f) * cross(n, edge);
  b.addGradient(m, t.tension * areaGradient);
  b.addOuter(m, t.tension * dot(edge, edge) / (F(2.0f) * twiceArea), n);
  b.addOuter(m, t.slope, areaGradient);
}

// a x = b by the adjugate, a given by rows.
template <class F>
Vec<F> solveByAdjugate(const std::array<std::array<F, 3>, 3>& a, const Vec<F>& b) {
  const F c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1], c01 = a[0][2] * a[2][1] - a[0][1] * a[2][2],
          c02 = a[0][1] * a[1][2] - a[0][2] * a[1][1];
  const F c10 = a[1][2] * a[2][0] - a[1][0] * a[2][2], c11 = a[0][0] * a[2][2] - a[0][2] * a[2][0],
          c12 = a[0][2] * a[1][0] - a[0][0] * a[1][2];
  const F c20 = a[1][0] * a[2][1] - a[1][1] * a[2][0], c21 = a[0][1] * a[2][0] - a[0][0] * a[2][1],
          c22 = a[0][0] * a[1][1] - a[0][1] * a[1][0];
  const F det = a[0][0] * c00 + a[0][1] * c10 + a[0][2] * c20;
  return Vec<F>{c00 * b.x + c01 * b.y + c02 * b.z, c10 * b.x + c11 * b.y + c12 * b.z,
                c20 * b.x + c21 * b.y + c22 * b.z} /
         det;
}

// A sweep moves a particle at most kTrustRegion of its shortest spring. The area energy of the physical model
// has no curvature in the film's plane (A is linear in a corner's height), so there the Newton step is only held
// by the film's small inertia and would fold triangles over. (A step within the limit is multiplied by 1, exactly.)
template <class F>
Vec<F> withinTrustRegionOf(const Vec<F>& step, F shortestSpring) {
  const F limit = F(kTrustRegion) * shortestSpring, length = norm(step);
  return select(length > limit, limit / length, F(1.0f)) * step;
}

template <class F>
F transverseStiffnessOf(F stiffness, F rest, F length) {
  return stiffness * max(F(0.0f), F(1.0f) - rest / length);
}

}  // namespace

float springEnergy(const State& s, size_t i, size_t j, float length, float rest) {
  return springEnergyOf(springStiffness(s, i, j), length - rest);
}

float transverseStiffness(float stiffness, float rest, float length) {
  return transverseStiffnessOf(stiffness, rest, length);
}

float triangleTension(const State& s, const uint32_t* corners) {
  return (s.elasticity[corners[0]] + s.elasticity[corners[1]] + s.elasticity[corners[2]]) / 3.0f;
}

float triangleTensionAt(const Params& p, float startTension, float startArea, float area) {
  return triangleTensionOf(p, startTension, startArea, area).tension;
}

float triangleTensionSlope(const Params& p, float startTension, float startArea, float area) {
  return triangleTensionOf(p, startTension, startArea, area).slope;
}

double triangleTensionEnergy(const Params& p, float startTension, float startArea, double area) {
  const double gibbs = p.gibbsElasticity, t0 = startTension, a0 = startArea;
  if (!(gibbs > 0 && a0 > 0 && area > 0)) return t0 * area;
  // Between the areas where the law reaches its clamps, T = T_0 + E_G ln r, r = A / A_0, integrates to
  // T_0 A + E_G A_0 (r ln r - r + 1); beyond them the tension is the clamp's, from the area where it was reached.
  const double r = area / a0, lnR = std::log(r), unclamped = t0 + gibbs * lnR;
  const double lowest = lowestTension(p.surfaceTension), highest = highestTension(p.surfaceTension);
  if (lowest <= unclamped && unclamped <= highest) return t0 * area + gibbs * a0 * (r * lnR - r + 1.0);
  const double held = unclamped < lowest ? lowest : highest, lnReached = (held - t0) / gibbs;
  const double reached = std::exp(lnReached);
  return t0 * a0 * reached + gibbs * a0 * (reached * lnReached - reached + 1.0) + held * (area - a0 * reached);
}

namespace {

// The k-th entry of each lane's range [offset[i], offset[i + 1]) of a CSR list, and which lanes have one. A lane
// without one reads the longest range's entry instead (a valid index whenever the loop runs; its terms are
// masked off).
template <class F>
struct Ranges {
  Particles<F> first{}, count{};
  uint32_t longest = 0, fallback = 0;
  Ranges(const std::vector<uint32_t>& offset, const Particles<F>& i, const std::array<bool, kLanes<F>>& active) {
    for (int l = 0; l < kLanes<F>; ++l) {
      first[l] = offset[i[l]];
      count[l] = active[l] ? offset[i[l] + 1] - first[l] : 0;
      if (count[l] > longest) longest = count[l], fallback = first[l];
    }
  }
  [[nodiscard]] MaskOf<F> has(uint32_t k) const {
    return maskFromLanes<F>([&](int l) { return k < count[l]; });
  }
  [[nodiscard]] uint32_t entry(int l, uint32_t k) const { return k < count[l] ? first[l] + k : fallback + k; }
};

// The corners of a triangle after one of its corners (3 t + c, Topology::triangleCorner), counter-clockwise.
struct CornersAfter {
  uint32_t next, last;
};
CornersAfter cornersAfter(const Topology& topo, uint32_t corner) {
  const uint32_t* tri = topo.triangleOf(corner);
  return {tri[(corner + 1) % 3], tri[(corner + 2) % 3]};
}

// A triangle's tension and area where the step started (triangleTension, triangleAreaAtStart).
template <class F>
struct TriangleStart {
  F tension, area;
};

// One particle's one-ring read from the topology's lists (objectiveBlock).
struct ListedRing {
  const Topology& topo;
  const State& s;
  uint32_t i;
  [[nodiscard]] uint32_t springs() const { return topo.springOffset[i + 1] - topo.springOffset[i]; }
  [[nodiscard]] bool hasSpring(uint32_t) const { return true; }
  [[nodiscard]] Particles<float> springNeighbour(uint32_t k) const {
    return {topo.springNeighbour[topo.springOffset[i] + k]};
  }
  [[nodiscard]] Vec<float> springNeighbourStart(uint32_t k) const {
    return gatherVec<float>(s.previousPosition, springNeighbour(k));
  }
  [[nodiscard]] float springStiffness(uint32_t k) const { return gb::springStiffness(s, i, springNeighbour(k)[0]); }
  [[nodiscard]] float springRest(uint32_t k) const {
    return topo.restLength[topo.springIndex[topo.springOffset[i] + k]];
  }
  [[nodiscard]] uint32_t triangles() const { return topo.triangleOffset[i + 1] - topo.triangleOffset[i]; }
  [[nodiscard]] bool hasTriangle(uint32_t) const { return true; }
  // The tension and area of i's k-th triangle where the step started, and its corners after i counter-clockwise.
  TriangleStart<float> triangle(uint32_t k, Particles<float>& next, Particles<float>& last) const {
    const uint32_t corner = topo.triangleCorner[topo.triangleOffset[i] + k];
    const uint32_t* tri = topo.triangleOf(corner);
    const CornersAfter corners = cornersAfter(topo, corner);
    next = {corners.next};
    last = {corners.last};
    return {triangleTension(s, tri), triangleAreaAtStart(topo, s, tri)};
  }
};

// Four particles' one-rings read from a run of SweepRuns (vertexBlockDescentRun).
struct RunRing {
  const SweepRuns& runs;
  uint32_t run;
  [[nodiscard]] uint32_t springs() const { return runs.springSlot[run + 1] - runs.springSlot[run]; }
  [[nodiscard]] Mask4 hasSpring(uint32_t k) const { return Mask4::below(&runs.springCount[4 * run], k); }
  [[nodiscard]] const uint32_t* springNeighbour(uint32_t k) const {
    return &runs.springNeighbour[4 * (runs.springSlot[run] + k)];
  }
  [[nodiscard]] Vec<Float4> springNeighbourStart(uint32_t k) const {
    const size_t slot = 4 * size_t{runs.springSlot[run] + k};
    const Vec3Array& start = runs.springNeighbourStart;
    return {Float4::load(&start.x[slot]), Float4::load(&start.y[slot]), Float4::load(&start.z[slot])};
  }
  [[nodiscard]] Float4 springStiffness(uint32_t k) const {
    return Float4::load(&runs.springStiffness[4 * (runs.springSlot[run] + k)]);
  }
  [[nodiscard]] Float4 springRest(uint32_t k) const {
    return Float4::load(&runs.springRest[4 * (runs.springSlot[run] + k)]);
  }
  [[nodiscard]] uint32_t triangles() const { return runs.triangleSlot[run + 1] - runs.triangleSlot[run]; }
  [[nodiscard]] Mask4 hasTriangle(uint32_t k) const { return Mask4::below(&runs.triangleCount[4 * run], k); }
  TriangleStart<Float4> triangle(uint32_t k, const uint32_t*& next, const uint32_t*& last) const {
    const size_t slot = 4 * (runs.triangleSlot[run] + k);
    next = &runs.cornerNext[slot];
    last = &runs.cornerLast[slot];
    return {Float4::load(&runs.triangleTension[slot]), Float4::load(&runs.triangleStartArea[slot])};
  }
};

// The internal energies and dissipations of the lanes' particles i at their current positions, their one-rings
// read from ring.
template <class F, class Ring>
void addInternal(const Params& p, float h, const Topology& topo, const State& s, const Particles<F>& i,
                 const std::array<bool, kLanes<F>>& active, const Ring& ring, const Vec<F>& x, const Vec<F>& dx,
                 BlockSum<F>& b) {
  const bool physical = p.tensionModel == 1;
  F isotropic = F(0.0f);  // Hessian terms proportional to the identity, added once at the end
  for (uint32_t k = 0; k < ring.springs(); ++k) {
    const auto j = ring.springNeighbour(k);
    const Vec<F> xj = gatherVec<F>(s.position, j);
    const Vec<F> d = xj - x;
    const F len = norm(d);
    const MaskOf<F> m = ring.hasSpring(k) && len > F(0.0f);
    if (none(m)) continue;
    const Vec<F> dir = d / len;
    b.shortestSpring = select(m, min(b.shortestSpring, len), b.shortestSpring);
    F along = addDampingGradient(m, F(p.springDamping), F(h), dir, dx - (xj - ring.springNeighbourStart(k)), b);
    if (!physical) {
      // The spring of Eq. (3), energy k/2 (len - l0)^2; Hessian k dir dir^T + k (1 - l0/len) (I - dir dir^T),
      // projected onto the positive semi-definite cone by dropping the transverse term of a compressed spring.
      const F stiffness = ring.springStiffness(k), rest = ring.springRest(k);
      b.subtractGradient(m, (stiffness * (len - rest)) * dir);
      const F transverse = transverseStiffnessOf(stiffness, rest, len);
      isotropic = isotropic + masked(m, transverse);
      along = along + (stiffness - transverse);
    }
    b.addOuter(m, along, dir);
  }
  b.addIsotropic(isotropic);
  if (physical) {
    for (uint32_t k = 0; k < ring.triangles(); ++k) {
      std::conditional_t<kLanes<F> == 1, Particles<float>, const uint32_t*> next, last;
      const TriangleStart<F> start = ring.triangle(k, next, last);
      addAreaTension(p, ring.hasTriangle(k), start.tension, start.area, x, gatherVec<F>(s.position, next),
                     gatherVec<F>(s.position, last), b);
    }
  }
  // Contacts: penalty k_c/2 (d_c - |x - xj|)^2 inside the pair's rest distance d_c (its transverse Hessian term is
  // negative and dropped), damped while the two approach. The partner is taken where inertia carries it,
  // x_t + h v_t, not where the sweep has moved it: contacts then need no colouring of their own, the colouring
  // changes only with the mesh, and the sweep's result does not depend on which contacts were found.
  const uint32_t base = static_cast<uint32_t>(s.size()) + 1;
  const Ranges<F> contacts(topo.contacts, i, active);
  const F stiffness = F(p.collisionStiffness);
  for (uint32_t k = 0; k < contacts.longest; ++k) {
    Particles<F> j;
    for (int l = 0; l < kLanes<F>; ++l) j[l] = topo.contacts[base + contacts.entry(l, k)];
    const Vec<F> xtj = gatherVec<F>(s.previousPosition, j);
    const Vec<F> xj = xtj + F(h) * gatherVec<F>(s.velocity, j);
    const Vec<F> d = x - xj;
    const F len = norm(d);
    const F rest =
        fromLanes<F>([&](int l) { return contactRestDistance(topo.contacts, s.size(), contacts.entry(l, k)); });
    const MaskOf<F> m = contacts.has(k) && len > F(0.0f) && len < rest;
    if (none(m)) continue;
    const Vec<F> away = d / len;
    b.subtractGradient(m, (stiffness * (rest - len)) * away);
    b.addOuter(m, stiffness, away);
    const Vec<F> relative = dx - (xj - xtj);
    const MaskOf<F> approaching = m && dot(relative, away) < F(0.0f);
    if (!none(approaching))
      b.addOuter(approaching, addDampingGradient(approaching, F(p.collisionDamping), F(h), away, relative, b), away);
  }
}

// What the inertia and drag terms need of a particle, fixed over the step: the target y = x_t + h v_t + h^2 f / m
// of implicit_euler.h, x_t, m / h^2, and the still-air drag coefficient / h.
template <class F>
struct InertialTerms {
  Vec<F> target, start;
  F inertia, drag;
};
InertialTerms<float> inertialTerms(const Params& p, float h, const State& s, size_t i) {
  const float m = s.mass[i];
  const Vec3 xt = s.previousPosition.get(i);
  return {lanesOf(xt + h * s.velocity.get(i) + (h * h / m) * s.force.get(i)), lanesOf(xt), m / (h * h),
          p.airDrag * s.voronoiArea[i] / h};
}

// The terms of a block before and after the internal ones: inertia and still-air drag, then the coupling to the
// moving air (its coefficient airCoupling) along the normal n of the step's start.
template <class F>
BlockSum<F> inertialBlock(const InertialTerms<F>& t, const Vec<F>& x) {
  BlockSum<F> b;
  b.gradient = t.inertia * (x - t.target) + t.drag * (x - t.start);
  b.addIsotropic(t.inertia + t.drag);
  return b;
}
template <class F>
void addAirCoupling(MaskOf<F> m, F coupling, F h, const Vec<F>& n, const Vec<F>& dx, BlockSum<F>& b) {
  b.addOuter(m, addDampingGradient(m, coupling, h, n, dx, b), n);
}
// breathingStiffness (implicit_euler.h) for one particle or four.
template <class F>
F breathingStiffnessOf(const Bubble& bubble, F area) {
  return bubble.volume > 0 ? F(bubble.pressure) * area * F(bubble.areaPerVolume) : F(0.0f);
}

// A closed bubble's gas: Boyle's pressure at the iterate's volume times the volume's gradient at the step's start
// (boyleForce), and breathingStiffness along the normal n of the step's start, for a particle of Voronoi area A.
template <class F>
void addGas(MaskOf<F> m, const Params& p, const Bubble& bubble, const Vec<F>& volumeGradient, F area, const Vec<F>& n,
            BlockSum<F>& b) {
  b.subtractGradient(m, F(boyleExcess(p, bubble.pressure)) * volumeGradient);
  b.addOuter(m, breathingStiffnessOf(bubble, area), n);
}

// The Newton step H^-1 g of a block by the adjugate (solveLinear3's operations on the symmetric entries).
template <class F>
Vec<F> solveSymmetric(const BlockSum<F>& b) {
  return solveByAdjugate<F>({{{b.xx, b.xy, b.xz}, {b.xy, b.yy, b.yz}, {b.xz, b.yz, b.zz}}}, b.gradient);
}

// Moves particle i by -step (then onto the floor); a non-finite step is left unapplied for the stability check
// to report.
inline void applyStep(State& s, size_t i, const Vec3& step) {
  if (!step.allFinite()) return;
  s.position.set(i, aboveFloor(s.position.get(i) - step));
}

}  // namespace

Vec3 solveLinear3(const Eigen::Matrix3f& a, const Vec3& b) {
  return eigenOf(solveByAdjugate<float>(
      {{{a(0, 0), a(0, 1), a(0, 2)}, {a(1, 0), a(1, 1), a(1, 2)}, {a(2, 0), a(2, 1), a(2, 2)}}}, lanesOf(b)));
}

Bubble bubbleOf(float volume, float pressure) {
  constexpr float sphereShape = 36.0f * 3.14159265f;  // A^3 = 36 pi V^2 for a sphere
  return {volume, pressure, volume > 0 ? std::cbrt(sphereShape / volume) : 0.0f};
}

float breathingStiffness(const Bubble& bubble, float area) { return breathingStiffnessOf(bubble, area); }

int sweepsThisStep(const Params& p, const StepUniforms& u) {
  return u.solverSweeps > 0 ? u.solverSweeps : p.solverSweeps;
}

std::array<float, kDriftTerms> externalDrift(const Topology& topo, const State& s, size_t i) {
  if (!s.alive[i] || topo.boundary[i]) return {};
  const Vec3 f = s.force.get(i);
  return {s.mass[i], f.x(), f.y(), f.z()};
}

Vec3 driftAcceleration(const std::array<float, kDriftTerms>& sums) {
  if (!(sums[0] > 0.0f)) return Vec3::Zero();
  return Vec3(sums[1], sums[2], sums[3]) / sums[0];
}

void implicitPredict(const StepUniforms& u, const Topology& topo, const Vec3& drift, State& s, size_t i) {
  if (!s.alive[i]) return;
  const Vec3 x = s.position.get(i);
  s.previousPosition.set(i, x);
  if (topo.boundary[i]) {
    if (s.wireParam[i] >= 0.0f) s.position.set(i, wirePoint(wireNextOf(u), s.wireParam[i]));
    return;
  }
  s.position.set(i, aboveFloor(x + u.dt * s.velocity.get(i) + (u.dt * u.dt) * drift));
}

VertexBlock objectiveBlock(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo,
                           const State& s, size_t i) {
  const InertialTerms<float> t = inertialTerms(p, u.dt, s, i);
  const Vec<float> x = lanesOf(s.position.get(i)), dx = x - t.start;
  BlockSum<float> b = inertialBlock(t, x);
  addInternal<float>(p, u.dt, topo, s, {static_cast<uint32_t>(i)}, {true},
                     ListedRing{topo, s, static_cast<uint32_t>(i)}, x, dx, b);
  addAirCoupling(true, airCoupling(p, u, s, i), u.dt, lanesOf(s.normal.get(i)), dx, b);
  if (u.closed)
    addGas<float>(true, p, bubble, lanesOf(volumeGradient(topo, s, i)), s.voronoiArea[i], lanesOf(s.normal.get(i)), b);
  return blockOf(b);
}

Vec3 trustedNewtonStep(const VertexBlock& b) {
  // The Hessian is at least (m / h^2) I, so it is invertible; a non-finite gradient gives a non-finite step,
  // which the caller leaves unapplied for the stability check to report.
  return withinTrustRegion(solveLinear3(b.hessian, b.gradient), b.shortestSpring);
}

Vec3 withinTrustRegion(Vec3 step, float shortestSpring) {
  return eigenOf(withinTrustRegionOf(lanesOf(step), shortestSpring));
}

Vec3 aboveFloor(Vec3 x) {
  x.y() = std::max(x.y(), 0.0f);
  return x;
}

void vertexBlockDescent(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo, State& s,
                        size_t i) {
  if (!s.alive[i]) return;  // died in a burst since the colouring was made
  applyStep(s, i, trustedNewtonStep(objectiveBlock(p, u, bubble, topo, s, i)));
}

namespace {

// Lane `lane` (4 r + l) of the runs: particle i, whether it is solved, its step constants and one-ring sizes.
void layOutLane(const Params& p, const StepUniforms& u, const Topology& topo, const State& s, uint32_t i, bool inColour,
                size_t lane, SweepRuns& runs) {
  const bool solved = inColour && s.alive[i];
  runs.particle[lane] = i;
  runs.solved[lane] = solved;
  const InertialTerms<float> t =
      solved ? inertialTerms(p, u.dt, s, i) : InertialTerms<float>{{0, 0, 0}, {0, 0, 0}, 0.0f, 0.0f};
  runs.target.set(lane, eigenOf(t.target));
  runs.start.set(lane, eigenOf(t.start));
  runs.normal.set(lane, solved ? s.normal.get(i) : Vec3::Zero());
  runs.inertia[lane] = t.inertia;
  runs.drag[lane] = t.drag;
  runs.airCoupling[lane] = solved ? airCoupling(p, u, s, i) : 0.0f;
  runs.volumeGradient.set(lane, solved && u.closed ? volumeGradient(topo, s, i) : Vec3::Zero());
  runs.area[lane] = solved ? s.voronoiArea[i] : 0.0f;
  runs.springCount[lane] = solved ? topo.springOffset[i + 1] - topo.springOffset[i] : 0;
  runs.triangleCount[lane] = solved && p.tensionModel == 1 ? topo.triangleOffset[i + 1] - topo.triangleOffset[i] : 0;
}

// The spring and triangle slots of run r.
void layOutSlots(const Params& p, const Topology& topo, const State& s, uint32_t r, SweepRuns& runs) {
  const bool physical = p.tensionModel == 1;
  const uint32_t filler = runs.particle[4 * r];
  for (uint32_t l = 0; l < 4; ++l) {
    const uint32_t i = runs.particle[4 * r + l];
    for (uint32_t k = 0; k < runs.springSlot[r + 1] - runs.springSlot[r]; ++k) {
      const size_t slot = 4 * size_t{runs.springSlot[r] + k} + l;
      const bool has = k < runs.springCount[4 * r + l];
      const uint32_t entry = topo.springOffset[i] + k, j = has ? topo.springNeighbour[entry] : filler;
      runs.springNeighbour[slot] = j;
      runs.springNeighbourStart.set(slot, s.previousPosition.get(j));
      runs.springStiffness[slot] = has && !physical ? springStiffness(s, i, j) : 0.0f;
      runs.springRest[slot] = has && !physical ? topo.restLength[topo.springIndex[entry]] : 0.0f;
    }
    for (uint32_t k = 0; k < runs.triangleSlot[r + 1] - runs.triangleSlot[r]; ++k) {
      const size_t slot = 4 * size_t{runs.triangleSlot[r] + k} + l;
      CornersAfter corners{filler, filler};
      float tension = 0.0f, startArea = 0.0f;
      if (k < runs.triangleCount[4 * r + l]) {
        const uint32_t corner = topo.triangleCorner[topo.triangleOffset[i] + k];
        const uint32_t* tri = topo.triangleOf(corner);
        corners = cornersAfter(topo, corner);
        tension = triangleTension(s, tri);
        startArea = triangleAreaAtStart(topo, s, tri);
      }
      runs.cornerNext[slot] = corners.next;
      runs.cornerLast[slot] = corners.last;
      runs.triangleTension[slot] = tension;
      runs.triangleStartArea[slot] = startArea;
    }
  }
}

}  // namespace

void layOutSweepRuns(const Params& p, const StepUniforms& u, const Topology& topo, const State& s, SweepRuns& runs) {
  runs.colourRuns.assign(1, 0);
  std::vector<uint32_t>& first = runs.scratchFirst;  // each run's first entry in colourOrder, and its colour's end
  std::vector<uint32_t>& end = runs.scratchEnd;
  first.clear();
  end.clear();
  for (size_t c = 0; c + 1 < topo.colourOffset.size(); ++c) {
    for (uint32_t k = topo.colourOffset[c]; k < topo.colourOffset[c + 1]; k += 4) {
      first.push_back(k);
      end.push_back(topo.colourOffset[c + 1]);
    }
    runs.colourRuns.push_back(static_cast<uint32_t>(first.size()));
  }
  const auto count = static_cast<long>(first.size());
  for (auto* v : {&runs.particle, &runs.solved, &runs.springCount, &runs.triangleCount}) v->resize(4 * first.size());
  for (auto* v : {&runs.target, &runs.start, &runs.normal, &runs.volumeGradient}) v->fit(4 * first.size());
  for (auto* v : {&runs.inertia, &runs.drag, &runs.airCoupling, &runs.area}) v->resize(4 * first.size());
  runs.springSlot.resize(first.size() + 1);
  runs.triangleSlot.resize(first.size() + 1);
#pragma omp parallel for schedule(static)
  for (long r = 0; r < count; ++r) {
    uint32_t springs = 0, triangles = 0;  // the run's slots: its longest one-ring's springs and triangles
    for (uint32_t l = 0; l < 4; ++l) {
      const bool inColour = first[r] + l < end[r];
      const size_t lane = 4 * static_cast<size_t>(r) + l;
      layOutLane(p, u, topo, s, topo.colourOrder[inColour ? first[r] + l : first[r]], inColour, lane, runs);
      springs = std::max(springs, runs.springCount[lane]);
      triangles = std::max(triangles, runs.triangleCount[lane]);
    }
    runs.springSlot[r + 1] = springs;
    runs.triangleSlot[r + 1] = triangles;
  }
  runs.springSlot[0] = runs.triangleSlot[0] = 0;
  std::partial_sum(runs.springSlot.begin(), runs.springSlot.end(), runs.springSlot.begin());
  std::partial_sum(runs.triangleSlot.begin(), runs.triangleSlot.end(), runs.triangleSlot.begin());
  const size_t springSlots = 4 * size_t{runs.springSlot.back()}, triangleSlots = 4 * size_t{runs.triangleSlot.back()};
  for (auto* v : {&runs.springNeighbour, &runs.cornerNext, &runs.cornerLast})
    v->resize(v == &runs.springNeighbour ? springSlots : triangleSlots);
  runs.springNeighbourStart.fit(springSlots);
  for (auto* v : {&runs.springStiffness, &runs.springRest, &runs.triangleTension, &runs.triangleStartArea})
    v->resize(v == &runs.triangleTension || v == &runs.triangleStartArea ? triangleSlots : springSlots);
#pragma omp parallel for schedule(static)
  for (long r = 0; r < count; ++r) layOutSlots(p, topo, s, static_cast<uint32_t>(r), runs);
}

void vertexBlockDescentRun(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo, State& s,
                           const SweepRuns& runs, uint32_t run) {
  const size_t at = 4 * size_t{run};
  const auto lanes = [&](const Vec3Array& a) {
    return Vec<Float4>{Float4::load(&a.x[at]), Float4::load(&a.y[at]), Float4::load(&a.z[at])};
  };
  Particles<Float4> i{};
  std::array<bool, 4> solved{};
  for (uint32_t l = 0; l < 4; ++l) {
    i[l] = runs.particle[at + l];
    solved[l] = runs.solved[at + l] != 0;
  }
  const InertialTerms<Float4> t{lanes(runs.target), lanes(runs.start), Float4::load(&runs.inertia[at]),
                                Float4::load(&runs.drag[at])};
  const Vec<Float4> x = gatherVec<Float4>(s.position, i), dx = x - t.start;
  BlockSum<Float4> b = inertialBlock(t, x);
  addInternal<Float4>(p, u.dt, topo, s, i, solved, RunRing{runs, run}, x, dx, b);
  const Mask4 live = Mask4::of(solved[0], solved[1], solved[2], solved[3]);
  addAirCoupling(live, Float4::load(&runs.airCoupling[at]), Float4(u.dt), lanes(runs.normal), dx, b);
  if (u.closed)
    addGas(live, p, bubble, lanes(runs.volumeGradient), Float4::load(&runs.area[at]), lanes(runs.normal), b);
  const Vec<Float4> step = withinTrustRegionOf(solveSymmetric(b), b.shortestSpring);
  for (int l = 0; l < 4; ++l)  // the lanes' particles share no term, so each moves on its own
    if (solved[l]) applyStep(s, i[l], Vec3(step.x.lane(l), step.y.lane(l), step.z.lane(l)));
}

double implicitResidual(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo,
                        const State& s) {
  double sum = 0;
  for (uint32_t i : topo.colourOrder)
    sum += objectiveBlock(p, u, bubble, topo, s, i).gradient.cast<double>().squaredNorm();
  return std::sqrt(sum);
}

void implicitVelocity(const StepUniforms& u, const Topology& topo, const VelocityBudget& budget, State& s, size_t i) {
  if (!s.alive[i]) return;
  const Vec3 v = (s.position.get(i) - s.previousPosition.get(i)) / u.dt;
  s.velocity.set(i, topo.boundary[i] ? v : budgetedVelocity(budget, v));
}

}  // namespace gb
