#pragma once
// The implicit step's coarse correction (docs/model.md "Integrators", "Coarse correction"). Vertex block descent
// moves a particle against its one-ring only, so a sweep reaches a film-wide mode hardly at all: on a bulged
// 2,000-particle film 6 sweeps do a third of the step's pull-back (coarse_correction_test), the mode keeps moving on
// the first guess while its restoring force is barely applied, and a film swinging at rest gains energy
// (docs/performance.md, the stress runs). The correction
// solves the step's Newton system restricted to rigid moves of patches of particles, a two-level scheme with
// unsmoothed aggregation (Vanek, Mandel, Brezina 1996): with P the patch-constant prolongation,
//
//   (P^T H P) d = -P^T g,   x_i += d_patch(i),
//
// H the projected Hessian of the step's objective (objectiveBlock's diagonal blocks and the springs' and
// triangles' off-diagonal blocks, as Newton-PCG in research/solver_comparison.h uses them), g its gradient at the
// iterate. Springs inside a patch cancel (a rigid move does not stretch them), so the patch system holds the inertia
// and the springs across patch borders: it is small (329 patches, 987 unknowns on the default film) and is solved by
// block-Jacobi preconditioned conjugate gradients. The correction leaves jumps at the patch borders, which the
// sweeps after it smooth away.

#include <cstdint>
#include <vector>

#include "solver/implicit_euler.h"

namespace gb {

inline constexpr uint32_t kNoPatch = ~0u;

// How many of the step's sweeps run before the coarse correction: half of them, rounded down, so that the
// correction sees a residual the sweeps before it have smoothed and the sweeps after it smooth the patch borders
// (a two-level V-cycle); -1 when the correction is off (Params::coarseIterations 0).
int coarseSweepsBefore(const Params& p, const StepUniforms& u);

// Groups the solver's particles (the living interior ones, Topology::colourOrder) into patches: seeds in increasing
// particle index, each taking the unclaimed solver particles within `rings` spring rings of it (breadth first);
// a patch left with fewer than a third of a full patch's particles then joins the neighbouring patch it shares
// the most springs with. Fills Topology's patch lists (state.h); wire and dead particles get kNoPatch.
void groupIntoPatches(const std::vector<uint32_t>& alive, int rings, Topology& topo);

// Groups the film's particles unless its topology already has patches of that many rings. The steppers call it
// when a film is loaded with the correction on (Params::coarseIterations > 0); with it off there are no patches.
void ensurePatches(const std::vector<uint32_t>& alive, int rings, Topology& topo);

// The off-diagonal blocks d^2 J / dx_i dx_j of the step's projected Hessian (implicit_euler.h) at positions x:
// spring k of i's one-ring (CSR entry), and corner l != c of triangle tri (c i's corner; physical model).
Eigen::Matrix3f springCouplingBlock(const Params& p, float h, const Topology& topo, const State& s, const Vec3Array& x,
                                    size_t i, uint32_t k);
Eigen::Matrix3f triangleCouplingBlock(const Params& p, const Topology& topo, const State& s, const Vec3Array& x,
                                      const uint32_t* tri, uint32_t c, uint32_t l);

// The patch system of one correction, P^T H P in 3x3 blocks laid out as Topology::patchRow, and its right-hand
// side -P^T g; then its solution.
struct CoarseSystem {
  std::vector<Eigen::Matrix3f> blocks;  // one per patchRow entry
  Vec3Array rightHandSide;              // per patch, N
  std::vector<float> shortestSpring;    // per patch: the shortest spring of its particles' one-rings (m)
  Vec3Array solution;                   // per patch: the move d (m)
  Vec3Array residual, direction, preconditioned, product;  // conjugate gradients' own
};

// Sizes the system's arrays for the topology's patches.
void fitCoarseSystem(const Topology& topo, CoarseSystem& system);

// Pass 1, per patch: its row of P^T H P and its entry of -P^T g at the film's current positions, gathered over its
// particles in increasing index and over each one's springs (and triangles) in CSR order.
void coarseAssemble(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo, const State& s,
                    size_t patch, CoarseSystem& system);

// Pass 2: `iterations` of conjugate gradients from d = 0, preconditioned by the inverse diagonal blocks; the dot
// products are tree sums (treeSum) over the patches in order. Stops early when the search direction has no
// curvature left (the system is solved to float precision).
void coarseSolve(const Topology& topo, int iterations, CoarseSystem& system);

// Pass 3, per particle i: moves a solver particle by its patch's d, shortened to the patch's shortest spring, then
// onto the floor. A non-finite move is left unapplied for the stability
// check to report.
void coarseApply(const Topology& topo, const CoarseSystem& system, State& s, size_t i);

}  // namespace gb
