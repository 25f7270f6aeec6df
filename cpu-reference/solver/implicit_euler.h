#pragma once
// The implicit step (docs/model.md "Integrators"): implicit Euler written as an optimisation (Martin et al.,
// "Example-based elastic materials", 2011; Gast et al., "Optimization integrator for large time steps",
// 2015):
//
//   x_{t+h} = argmin_x  1/(2 h^2) |x - y|_M^2 + E(x) + D(x),   y = x_t + h v_t + h^2 M^-1 f_ext,
//
// E the internal energies (springs of Eq. 3 with the elasticity of Eq. 4 frozen over the step, or the
// physical 2 gamma x area, the contact penalty, and for a closed bubble the isothermal gas, whose gradient is
// Boyle's excess pressure, Eqs. 10-11, at the iterate's volume), D the dissipation of the spring damping (Algorithm 1),
// the contacts' damping and the air drag, all in the velocity (x - x_t) / h. The wire's particles are
// prescribed. Solved by Vertex Block Descent (Chen, Liu, Yang, Yuksel, ACM TOG 43(4), 2024): each particle
// in turn takes one Newton step on the objective with all other particles fixed, a 3x3 solve with the
// positive semi-definite part of its Hessian; particles of one colour (colouring.h) are independent and
// are solved in parallel, colours one after the other. Every particle step lowers the objective, so the
// step is stable at any h; a fixed number of sweeps leaves the stiffest long waves under-resolved, which
// acts as numerical damping (docs/model.md measures it).

#include <array>
#include <limits>
#include <vector>

#include "kernels/shared/shared_step.h"
#include "stages/stages.h"

namespace gb {

// Solves a x = b for a 3x3 matrix by its adjugate (the same float operations as the shader's twin).
Vec3 solveLinear3(const Eigen::Matrix3f& a, const Vec3& b);

// A closed bubble's volume and Boyle pressure at the solver's current iterate (recomputed before each sweep);
// unused for an open film.
struct Bubble {
  float volume = 0.0f;         // m^3
  float pressure = 0.0f;       // P_cur of Eq. (11), Pa
  float areaPerVolume = 0.0f;  // A_total / V of a sphere of this volume, (36 pi / V)^(1/3) (1/m); 0 without one
};
// A closed film's gas at an iterate: its volume and Boyle's pressure, with the sphere's area per volume that
// breathingStiffness takes, worked out once per sweep rather than at every particle (a cube root each would be 4%
// of the default run's time).
Bubble bubbleOf(float volume, float pressure);

// The stiffness of the bubble's breathing seen by one particle of area A: P A A_total / V, the pressure change
// when the whole bubble swells, with A_total = (36 pi V^2)^(1/3) as for a sphere. Added to the particle's
// Hessian along its normal so that a colour of particles moving out together under a stale volume cannot
// overshoot; it changes how fast the sweeps converge, not what they converge to.
float breathingStiffness(const Bubble& bubble, float area);

// The terms of the objective that the solvers of research/solver_comparison.h also build their Hessian from:
// the paper's spring between i and j has stiffness (E_i + E_j) / 2 (N/m), and its Hessian k dir dir^T +
// k (1 - l0/len) (I - dir dir^T) keeps the transverse part only while stretched (projected onto the positive
// semi-definite cone); a triangle of the physical model pulls with the mean 2 gamma of its corners (N/m).
inline float springStiffness(const State& s, size_t i, size_t j) { return 0.5f * (s.elasticity[i] + s.elasticity[j]); }
// The energy k/2 (length - rest)^2 of the spring between i and j (Eq. 3, k = springStiffness) at this length.
float springEnergy(const State& s, size_t i, size_t j, float length, float rest);
float transverseStiffness(float stiffness, float rest, float length);
float triangleTension(const State& s, const uint32_t* corners);
// The tension of a triangle whose area went from startArea, where the step started, to area. Its surfactant moves
// with it, so its gamma follows filmTension's Gibbs law in the triangle's own area (E_G = 2 d gamma / d ln A),
// from the tension its corners gave it at the start (triangleTension), clamped as filmTension clamps: the
// physical model's Gibbs elasticity, implicit in the step (docs/model.md).
float triangleTensionAt(const Params& p, float startTension, float startArea, float area);
// Its slope dT/dA: E_G / A, or 0 where the tension is clamped or the law does not apply.
float triangleTensionSlope(const Params& p, float startTension, float startArea, float area);
// The energy of such a triangle at `area`: startTension x startArea at the start, and its derivative in the area
// is triangleTensionAt. In double: the Gibbs part is a small difference of large terms near the start.
double triangleTensionEnergy(const Params& p, float startTension, float startArea, double area);

// The gradient (N) and Hessian (N/m) of the step's objective in x_i with every other particle fixed, summed
// term by term; the Hessian is projected to be positive semi-definite (docs/model.md "Integrators") and holds
// at least (m / h^2) I.
struct VertexBlock {
  Vec3 gradient = Vec3::Zero();
  Eigen::Matrix3f hessian = Eigen::Matrix3f::Zero();
  float shortestSpring = std::numeric_limits<float>::infinity();  // of the particle's one-ring (m)
};
VertexBlock objectiveBlock(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo,
                           const State& s, size_t i);

// The Newton step H^-1 g of a particle's block, shortened to the trust region (a quarter of its shortest
// one-ring spring); the particle moves to x - step. Non-finite when the gradient is.
Vec3 trustedNewtonStep(const VertexBlock& b);
// A particle's step shortened to the trust region (kTrustRegion of its shortest one-ring spring, m).
Vec3 withinTrustRegion(Vec3 step, float shortestSpring);

// The floor, y = 0: a solved position never goes below it.
Vec3 aboveFloor(Vec3 x);

// Vertex block descent sweeps of a step: the step's own count (the live loop lowers it under load), else
// Params::solverSweeps.
int sweepsThisStep(const Params& p, const StepUniforms& u);

// Stage external_drift (a closed film's implicit step), per particle i: its share of the film's drift, its mass and
// the explicit force on it, {m, f_x, f_y, f_z}; zero for a wire or dead particle. The shares are summed in the tree
// order of the volume on both backends. Why: a sweep moves one particle at a time against its springs, and a move of
// every particle together, the film's centre of mass, is the slowest of all to build up that way. Started from
// x_t + h v_t, a stiff free bubble kept its velocity whatever gravity did (docs/model.md, "The first guess").
constexpr size_t kDriftTerms = GB_DRIFT_TERMS;
std::array<float, kDriftTerms> externalDrift(const Topology& topo, const State& s, size_t i);

// The acceleration of a closed film's centre of mass from the sums of externalDrift (m/s^2): sum f / sum m, zero
// without mass.
Vec3 driftAcceleration(const std::array<float, kDriftTerms>& sums);

// Stage implicit_predict, per particle i: keeps x_t in previousPosition; a wire particle is placed on the
// wire frame at the end of the step (or stays, pinned), an interior particle starts from x_t + h v_t + h^2 a,
// a the film's drift (driftAcceleration; zero for an open film, whose wire holds it), above the floor.
void implicitPredict(const StepUniforms& u, const Topology& topo, const Vec3& drift, State& s, size_t i);

// Stage vertex_block_descent, per particle i of the colour being swept: one Newton step on the objective
// restricted to x_i, then the floor. Reads the external force of the external_forces stage and x_t.
void vertexBlockDescent(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo, State& s,
                        size_t i);

// The CPU stepper's sweeps take the particles of a colour four at a time, in the lanes of a vector register
// (float_lanes.h), with their one-rings laid out once per step as below: slot k of a run holds the k-th
// spring (triangle) of each of its four particles side by side, so that a sweep reads four neighbours'
// indices with one load, and what the sweeps would recompute unchanged (a spring's stiffness, a triangle's
// tension and area at the step's start: the elasticity is frozen over the step; the corners after i; a closed
// film's volume gradient, from the start's normals) is there already.
struct SweepRuns {
  std::vector<uint32_t> colourRuns;  // colour c's runs are [colourRuns[c], colourRuns[c + 1])
  // Four per run: the particles (a lane past the colour's end repeats lane 0's), whether each is solved
  // (living, not past the end), and how many springs and triangles of its one-ring are in the run's slots.
  std::vector<uint32_t> particle, solved, springCount, triangleCount;
  // Four per run, fixed over the step: each solved particle's target y, x_t, the normal n of the step's start, a
  // closed film's volumeGradient (stages.h), m / h^2, the still-air drag / h, airCoupling and the Voronoi area
  // (zeros in a lane not solved).
  Vec3Array target, start, normal, volumeGradient;
  std::vector<float> inertia, drag, airCoupling, area;
  std::vector<uint32_t> springSlot, triangleSlot;  // run r's slots are [slot[r], slot[r + 1])
  // Four per slot; a lane without a spring (triangle) there holds lane 0's particle (its x_t in
  // springNeighbourStart) and zeros, masked off.
  std::vector<uint32_t> springNeighbour;
  Vec3Array springNeighbourStart;                  // the neighbour's x_t, read by the spring's damping every sweep
  std::vector<float> springStiffness, springRest;  // springStiffness, restLength (springs model only)
  std::vector<uint32_t> cornerNext, cornerLast;    // the triangle's corners after i, counter-clockwise
  std::vector<float> triangleTension;              // triangleTension (physical model only)
  std::vector<float> triangleStartArea;            // triangleAreaAtStart (physical model only)
  std::vector<uint32_t> scratchFirst, scratchEnd;  // layOutSweepRuns' own, kept to reuse their memory
};
void layOutSweepRuns(const Params& p, const StepUniforms& u, const Topology& topo, const State& s, SweepRuns& runs);

// vertexBlockDescent for the four particles of run r of SweepRuns, each particle's result the same bit for bit.
void vertexBlockDescentRun(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo, State& s,
                           const SweepRuns& runs, uint32_t run);

// Diagnostic (CPU, double): the norm of the objective's gradient over the solved particles, in N: zero when
// the step is solved exactly (docs/model.md's convergence figures, tests).
double implicitResidual(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo,
                        const State& s);

struct VelocityBudget;
// Stage implicit_velocity, per particle i: v = (x - x_t) / h, the implicit Euler velocity, a free particle's as the
// energy budget leaves it (energy_budget.h; unchanged without one).
void implicitVelocity(const StepUniforms& u, const Topology& topo, const VelocityBudget& budget, State& s, size_t i);

}  // namespace gb
