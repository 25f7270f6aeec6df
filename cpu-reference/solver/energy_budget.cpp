#include "solver/energy_budget.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "solver/implicit_euler.h"
#include "solver/particle_lanes.h"

namespace gb {

namespace {

// Particle i's share of the internal energy E, at the step's start and at its end, in one pass over its one-ring:
// its springs' or triangles' pieces (heldPiece) and half of each contact's penalty (k_c/2 (d_c - len)^2 inside its
// rest distance d_c).
struct HeldShares {
  float start = 0.0f, end = 0.0f;
};
HeldShares heldShares(const Params& p, const Topology& topo, const State& s, const HeldPieces& pieces, uint32_t i) {
  HeldShares h;
  if (p.tensionModel == 1) {
    for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k) {
      const uint32_t t = topo.triangleCorner[k] / 3;
      h.start += pieces.start[t];
      h.end += pieces.end[t];
    }
  } else {
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
      const uint32_t spring = topo.springIndex[k];
      h.start += pieces.start[spring];
      h.end += pieces.end[spring];
    }
  }
  const Vec3 xi = s.position.get(i), xi0 = positionAtStepStart(topo, s, i);
  const uint32_t base = static_cast<uint32_t>(s.size()) + 1;
  for (uint32_t k = topo.contacts[i]; k < topo.contacts[i + 1]; ++k) {
    const uint32_t j = topo.contacts[base + k];
    const float rest = contactRestDistance(topo.contacts, s.size(), k);
    const float len0 = (xi0 - positionAtStepStart(topo, s, j)).norm(), len = (xi - s.position.get(j)).norm();
    if (len0 < rest) h.start += 0.5f * springEnergyOf(p.collisionStiffness, rest - len0);
    if (len < rest) h.end += 0.5f * springEnergyOf(p.collisionStiffness, rest - len);
  }
  return h;
}

}  // namespace

size_t heldPieceCount(const Params& p, const Topology& topo) {
  return p.tensionModel == 1 ? topo.triangleCount() : topo.springCount();
}

namespace {

void trianglePiece(const Params& p, const Topology& topo, const State& s, size_t t, HeldPieces& pieces) {
  const uint32_t* tri = &topo.triangles[3 * t];
  const float tension = triangleTension(s, tri), area0 = triangleAreaAtStart(topo, s, tri);
  const Vec3 a = s.position.get(tri[0]);
  const float area = 0.5f * (s.position.get(tri[1]) - a).cross(s.position.get(tri[2]) - a).norm();
  pieces.start[t] = tension * area0 / 3.0f;
  pieces.end[t] = static_cast<float>(triangleTensionEnergy(p, tension, area0, area)) / 3.0f;
}

// The pieces of the springs from `first` on, one in each lane of F: the float operations of Eigen's norm and of
// springEnergyOf in each lane, the same floats for one spring and for four.
template <class F>
void springPieces(const Topology& topo, const State& s, size_t first, HeldPieces& pieces) {
  constexpr int kCount = kLanes<F>;
  std::array<Vec3, kCount> a, b, a0, b0;  // the ends now and at the step's start
  std::array<float, kCount> stiffness, rest;
  for (int l = 0; l < kCount; ++l) {
    const size_t spring = first + static_cast<size_t>(l);
    const uint32_t i = topo.springEnds[2 * spring], j = topo.springEnds[2 * spring + 1];
    a[l] = s.position.get(i), b[l] = s.position.get(j);
    a0[l] = positionAtStepStart(topo, s, i), b0[l] = positionAtStepStart(topo, s, j);
    stiffness[l] = springStiffness(s, i, j), rest[l] = topo.restLength[spring];
  }
  const auto lanes = [](const std::array<Vec3, kCount>& v) {
    return Vec3Of<F>{fromLanes<F>([&](int l) { return v[l].x(); }), fromLanes<F>([&](int l) { return v[l].y(); }),
                     fromLanes<F>([&](int l) { return v[l].z(); })};
  };
  const F k = fromLanes<F>([&](int l) { return stiffness[l]; }), l0 = fromLanes<F>([&](int l) { return rest[l]; });
  const F stretch0 = norm(lanes(b0) - lanes(a0)) - l0, stretch = norm(lanes(b) - lanes(a)) - l0;
  const F start = F(0.5f) * springEnergyOf(k, stretch0), end = F(0.5f) * springEnergyOf(k, stretch);  // each end's half
  if constexpr (kCount == 1) {
    pieces.start[first] = start, pieces.end[first] = end;
  } else {
    start.store(&pieces.start[first]);
    end.store(&pieces.end[first]);
  }
}

}  // namespace

void heldPieces(const Params& p, const Topology& topo, const State& s, size_t first, size_t last, HeldPieces& pieces) {
  if (p.tensionModel == 1) {
    for (size_t t = first; t < last; ++t) trianglePiece(p, topo, s, t, pieces);
    return;
  }
  size_t spring = first;
  for (; spring + 4 <= last; spring += 4) springPieces<Float4>(topo, s, spring, pieces);
  for (; spring < last; ++spring) springPieces<float>(topo, s, spring, pieces);
}

float triangleAreaAtStart(const Topology& topo, const State& s, const uint32_t* corners) {
  const Vec3 a0 = positionAtStepStart(topo, s, corners[0]);
  return 0.5f *
         (positionAtStepStart(topo, s, corners[1]) - a0).cross(positionAtStepStart(topo, s, corners[2]) - a0).norm();
}

float triangleVolumeAtStart(const Topology& topo, const State& s, size_t t, const Vec3& origin) {
  const uint32_t* tri = &topo.triangles[3 * t];
  return coneVolume(positionAtStepStart(topo, s, tri[0]), positionAtStepStart(topo, s, tri[1]),
                    positionAtStepStart(topo, s, tri[2]), origin);
}

ParticleEnergy energyTerms(const Params& p, const StepUniforms& u, const Topology& topo, const State& s,
                           const HeldPieces& pieces, size_t i) {
  if (!s.alive[i]) return {};
  const auto index = static_cast<uint32_t>(i);
  ParticleEnergy e;
  const HeldShares held = heldShares(p, topo, s, pieces, index);
  e.start = held.start;
  e.held = held.end;
  if (topo.boundary[i]) return e;  // the wire's particles are prescribed: their motion is the wands' work
  const float m = s.mass[i];
  const Vec3 moved = s.position.get(i) - s.previousPosition.get(i), v = moved / u.dt;
  e.start += 0.5f * m * s.velocity.get(i).squaredNorm();
  e.kinetic = 0.5f * m * v.squaredNorm();
  e.held -= s.force.get(i).dot(moved);
  e.mass = m;
  e.momentum = m * v;
  e.expected = u.closed ? Vec3(m * s.velocity.get(i) + u.dt * s.force.get(i)) : Vec3::Zero();
  return e;
}

float boyleEnergyChange(const Params& p, float referenceVolume, float before, float after) {
  if (!(before > 0.0f && after > 0.0f && referenceVolume > 0.0f)) return 0.0f;
  const float d = (after - before) / before;
  // d - ln(1 + d): by its series for a small change (float's log(1 + d) would lose it), else directly
  const float curvature =
      std::abs(d) < 0.1f
          ? d * d * (0.5f - d * (1.0f / 3.0f - d * (0.25f - d * (0.2f - d * (1.0f / 6.0f - d * (1.0f / 7.0f))))))
          : d - std::log(1.0f + d);
  return p.pressureCoefficient * ((before - referenceVolume) * d + referenceVolume * curvature);
}

Vec3 driftWithinBudget(const Vec3& expected, const Vec3& centre, float speedSquared) {
  const Vec3 made = centre - expected;  // the drift the step made itself
  const float a = made.squaredNorm(), b = expected.dot(made), c = expected.squaredNorm() - speedSquared;
  if (!(a > 0.0f)) return centre;
  // |expected + l made|^2 <= speedSquared for l between the roots of a l^2 + 2 b l + c.
  float l = std::clamp(-b / a, 0.0f, 1.0f);  // the least speed on the way, where no l will do
  const float discriminant = b * b - a * c;
  if (discriminant >= 0.0f) {
    const float root = std::sqrt(discriminant), lower = (-b - root) / a, upper = (-b + root) / a;
    if (upper >= 0.0f && lower <= 1.0f) l = std::min(upper, 1.0f);
  }
  return expected + l * made;
}

VelocityBudget energyScale(float start, float kinetic, float held, float mass, const Vec3& momentum,
                           const Vec3& expectedMomentum) {
  const float budget = start + kEnergyBudgetTolerance * std::abs(start);
  if (!std::isfinite(budget) || !std::isfinite(kinetic + held)) return {.released = 0.0f};
  if (!(kinetic + held > budget) || !(mass > 0.0f)) return {.released = std::max(0.0f, start - (kinetic + held))};
  const float drift = 0.5f * momentum.squaredNorm() / mass, internal = kinetic - drift;
  const float room = budget - held;  // the kinetic energy the step may end with
  const Vec3 centre = momentum / mass;
  if (room >= drift)  // the wobble holds the excess
    return {internal > 0.0f ? std::sqrt(std::clamp((room - drift) / internal, 0.0f, 1.0f)) : 1.0f, centre, Vec3::Zero(),
            0.0f};
  // Not even the drift was paid for: no wobble, and the drift given back as far as the film's own goes.
  return {0.0f, centre, driftWithinBudget(expectedMomentum / mass, centre, 2.0f * room / mass) - centre, 0.0f};
}

Vec3 budgetedVelocity(const VelocityBudget& budget, const Vec3& v) {
  return budget.acted() ? Vec3(budget.centre + budget.shift + budget.scale * (v - budget.centre)) : v;
}

}  // namespace gb
