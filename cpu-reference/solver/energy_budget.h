#pragma once
// The implicit step's energy budget (docs/model.md "Energy budget"). Implicit Euler solved exactly never gives
// the film more energy than the work done on it: with the wire placed first (the wands' work), the step's
// mechanical energy H = K + E (kinetic, springs or 2 gamma x area, contacts, the bubble's gas) satisfies
//
//   H(x_{t+h}, v_{t+h}) <= H(x_t with the wire placed, v_t) + sum_i f_ext,i . (x_{t+h} - x_t)
//
// for a convex E (Gast et al. 2015). A fixed number of sweeps stops short of the solution: the long waves
// keep the first guess x_t + h v_t, which stretches a swinging, crumpled film (the stress runs).
// Stage energy_budget checks the inequality after the sweeps; where the step broke it by more than
// kEnergyBudgetTolerance, the free particles' new velocities relative to their centre of mass are scaled down by
// the one factor that brings H back to the budget (implicit_velocity applies it): the film keeps its momentum (a
// sinking bubble keeps sinking) and gives up the excess from its wobble, or where even its drift was not paid for,
// from the drift too. The positions stay the solver's: a step that gains more potential energy than the motion
// holds ends at rest, and the next steps take the rest out as it turns into motion.

#include <limits>
#include <vector>

#include "kernels/shared/shared_step.h"
#include "stages/stages.h"

namespace gb {

// Relative slack of the budget, 1e-4 of the step's starting energy (GB_ENERGY_BUDGET_TOLERANCE, shared with the
// shaders). It covers the float sums of both backends (a tree sum of a million float terms is exact to ~1e-6 of
// its size) and the little a solved step can gain where E is not convex (a compressed spring, a contact); 40 steps
// of it stay far below the stress check's 2%.
inline constexpr float kEnergyBudgetTolerance = static_cast<float>(GB_ENERGY_BUDGET_TOLERANCE);

// Where particle i was at the step's start, as the budget counts it: x_t, or for a wire particle the place the
// wire put it at the step's end (the wands' work is done before the step).
inline Vec3 positionAtStepStart(const Topology& topo, const State& s, size_t i) {
  return topo.boundary[i] ? s.position.get(i) : s.previousPosition.get(i);
}

// triangleVolume (stages.h) at the step's start: the leaves of a closed bubble's volume before the step.
float triangleVolumeAtStart(const Topology& topo, const State& s, size_t t, const Vec3& origin);

// The area of the triangle with these corners at the step's start (positionAtStepStart of each).
float triangleAreaAtStart(const Topology& topo, const State& s, const uint32_t* corners);

// A particle's share of the step's energy (J): at the start (x_t, the wire placed at its end position, v_t),
// at the end its kinetic energy (v = (x - x_t) / h) and the rest (its share of E at x less the work the
// explicit forces did on it). Springs, triangles and contacts are shared equally among the particles they join.
// A free particle also gives its mass and its momentum at the end, for the centre of mass, and on a closed film the
// momentum it would have from its start and the explicit forces alone (m v_t + h f): the drift that is the film's
// own. An open film's wire sets its motion every step: none of its drift is its own (expected momentum 0).
struct ParticleEnergy {
  float start = 0.0f, kinetic = 0.0f, held = 0.0f;
  float mass = 0.0f;             // kg
  Vec3 momentum = Vec3::Zero();  // m v (kg m/s)
  Vec3 expected = Vec3::Zero();  // m v_t + h f (kg m/s)
};
// The internal energy E in pieces: each spring's (tension model 0) or triangle's (model 1) share of E held by each
// particle it joins, at the step's start and at its end: half of a spring's k/2 (len - l0)^2, a third of a triangle's
// triangleTensionEnergy. Computed once per piece (heldPieces), each piece is added by all of its particles; the device
// computes a particle's pieces in its own thread, to the same floats.
struct HeldPieces {
  std::vector<float> start, end;  // by spring or by triangle (heldPieceCount)
};
size_t heldPieceCount(const Params& p, const Topology& topo);
// Pieces [first, last) (springs four at a time), into `pieces`, whose arrays hold heldPieceCount.
void heldPieces(const Params& p, const Topology& topo, const State& s, size_t first, size_t last, HeldPieces& pieces);

ParticleEnergy energyTerms(const Params& p, const StepUniforms& u, const Topology& topo, const State& s,
                           const HeldPieces& pieces, size_t i);

// The isothermal gas's energy change P0 (V0 ln(V0 / V) + V - V0) from volume `before` to `after` (J), taken
// as a difference so that float keeps it: its first-order term is the excess pressure's work, tiny next to P0 V.
float boyleEnergyChange(const Params& p, float referenceVolume, float before, float after);

// What implicit_velocity does with a free particle's new velocity v: c + shift + scale (v - c), c the free
// particles' centre-of-mass velocity after the step. Scale 1 and no shift leave v as it is.
struct VelocityBudget {
  float scale = 1.0f;
  Vec3 centre = Vec3::Zero();  // m/s
  Vec3 shift = Vec3::Zero();   // m/s: the drift the step made itself, given back
  // J: how far the step ended below its budget, the energy its damping and solver took out (0 where the budget acted
  // or the sums are not finite). The rest-length rules between frames may put back this much (contractSlackSprings).
  // Infinite where no budget was kept (the explicit integrator, energyBudget 0): the rules are then not held to it.
  float released = std::numeric_limits<float>::infinity();
  [[nodiscard]] bool acted() const { return scale != 1.0f || shift != Vec3::Zero(); }
};
// The budget from the sums of the particles' terms: none when kinetic + held <= start (1 + kEnergyBudgetTolerance).
// Else the excess comes out of the motion about the centre of mass, by the factor
// sqrt((budget - held - drift) / (kinetic - drift)) clamped to [0, 1] (drift = |momentum|^2 / 2 mass). Where even the
// drift exceeds what is left, the wobble goes and the drift is given back down to what the budget has left, but not
// below the film's own (driftWithinBudget): the momentum a closed film had at the start and the explicit forces gave
// it (`expectedMomentum`, the sum of m v_t + h f). What it gives back there is what the step made itself: a closed
// film's own forces cannot move its centre, but its contacts, taken at their partners' first guess, do not push
// equally both ways. So a bubble blown off the wands keeps flying even where a step after the pinch-off gained more
// than all its motion holds; the positions keep the rest, which the next steps take out as it turns into motion. An
// open film has no drift of its own (its wire sets it): there the drift is slowed to what is left. No budget when
// the sums are not finite: the simulation's instability check reports that, not the budget.
VelocityBudget energyScale(float start, float kinetic, float held, float mass, const Vec3& momentum,
                           const Vec3& expectedMomentum);
// The centre's velocity on the way from `expected` to `centre` nearest `centre` whose squared speed is at most
// `speedSquared`; where none is, the one of least speed on that way.
Vec3 driftWithinBudget(const Vec3& expected, const Vec3& centre, float speedSquared);
// The velocity implicit_velocity gives a free particle whose unbudgeted one is v.
Vec3 budgetedVelocity(const VelocityBudget& budget, const Vec3& v);

}  // namespace gb
