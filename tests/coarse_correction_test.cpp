// The implicit step's coarse correction (cpu-reference/solver/coarse_correction.h): its patches, and what it adds to
// the sweeps on a film-wide mode.
#include "solver/coarse_correction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "capture/scripted_gestures.h"
#include "research/solver_comparison.h"
#include "simulation/simulation.h"
#include "solver/colouring.h"
#include "stages/cpu_stepper.h"

namespace gb {
namespace {

// Every solver particle lies in exactly one patch and no other particle in any; each patch is a neighbourhood of
// its seed (at most a full patch of `rings` rings plus the small patches merged into it); the rows list exactly the
// patches the springs join, themselves included, sorted, and the coupling is symmetric.
TEST(CoarseCorrection, PatchesHoldEverySolverParticleOnce) {
  Params p;
  p.particlesAtFullSolution = 2000;
  Simulation sim(p, WandTool{}, gestureAt(Gesture::Straight, GestureOptions{}, 0.0));
  Topology topo = sim.film().topology;
  const int rings = 3;
  groupIntoPatches(sim.film().state.alive, rings, topo);
  const size_t n = topo.particleCount(), patches = topo.patchOffset.size() - 1;
  std::vector<int> seen(n, 0);
  for (uint32_t patch = 0; patch < patches; ++patch)
    for (uint32_t m = topo.patchOffset[patch]; m < topo.patchOffset[patch + 1]; ++m) {
      const uint32_t i = topo.patchMembers[m];
      ++seen[i];
      EXPECT_EQ(topo.patchOf[i], patch);
    }
  for (size_t i = 0; i < n; ++i) {
    EXPECT_EQ(seen[i], isSolverParticle(sim.film().state.alive, sim.film().topology, i) ? 1 : 0) << "particle " << i;
    if (!isSolverParticle(sim.film().state.alive, sim.film().topology, i)) {
      EXPECT_EQ(topo.patchOf[i], kNoPatch);
    }
  }
  const size_t full = 1 + 3 * rings * (rings + 1);  // a hexagon of `rings` rings
  size_t largest = 0;
  for (uint32_t patch = 0; patch < patches; ++patch) {
    const size_t size = topo.patchOffset[patch + 1] - topo.patchOffset[patch];
    largest = std::max(largest, size);
    const auto first = topo.patchRow.begin() + topo.patchRowOffset[patch],
               last = topo.patchRow.begin() + topo.patchRowOffset[patch + 1];
    EXPECT_TRUE(std::is_sorted(first, last));
    EXPECT_TRUE(std::binary_search(first, last, patch)) << "patch " << patch << " is missing from its own row";
    for (auto other = first; other != last; ++other) {
      const auto otherFirst = topo.patchRow.begin() + topo.patchRowOffset[*other],
                 otherLast = topo.patchRow.begin() + topo.patchRowOffset[*other + 1];
      EXPECT_TRUE(std::binary_search(otherFirst, otherLast, patch)) << patch << " and " << *other;
    }
  }
  // A seed's patch holds at most its rings' particles; a merged one adds less than a third of that, more than
  // once only where several small ones border it (none on this film).
  EXPECT_LE(largest, full + full / 3) << "a patch is not a neighbourhood of its seed";
  std::printf("%zu solver particles in %zu patches (largest %zu, full %zu)\n", topo.colourOrder.size(), patches,
              largest, full);
}

// One step of a flat 2,000-particle film at rest, bulged out of its plane by up to 5 cm (a paraboloid from the wire
// to the centre): a film-wide mode whose restoring force the sweeps spread one spring per sweep, while the
// coarse correction reaches it at once. How far the step takes the bulge back, as its amplitude along the bulge's
// own shape (1: the first guess), and the step's objective (J).
struct BulgeResult {
  double amplitude, objective;
};
struct BulgeStep {
  BulgeResult first, sweepsAlone, withCoarse, converged;
};

BulgeStep bulgeStep() {
  Params p;
  p.particlesAtFullSolution = 2000;
  const WandState wands = gestureAt(Gesture::Straight, GestureOptions{}, 0.0);
  Simulation sim(p, WandTool{}, wands);
  Film start = sim.film();
  Vec3 centre = Vec3::Zero();
  for (size_t i = 0; i < start.state.size(); ++i) centre += start.state.position.get(i);
  centre /= static_cast<float>(start.state.size());
  float radius = 0.0f;
  for (size_t i = 0; i < start.state.size(); ++i)
    radius = std::max(radius, (start.state.position.get(i) - centre).norm());
  const Vec3Array flat = start.state.position;
  Vec3Array bulge;  // the displacement of the first guess
  bulge.resize(start.state.size());
  for (size_t i = 0; i < start.state.size(); ++i) {
    if (!isSolverParticle(start.state.alive, start.topology, i)) continue;
    const float r = (flat.get(i) - centre).norm() / radius;
    bulge.set(i, 0.05f * (1.0f - r * r) * start.state.normal.get(i));
    start.state.position.set(i, flat.get(i) + bulge.get(i));
  }
  const StepUniforms u = sim.uniformsFor(wands, wands, p.frameTime);
  auto solve = [&](int sweeps, int coarseIterations, bool stopBeforeSweeps) {
    Params q = p;
    q.solverSweeps = sweeps;
    q.coarseIterations = coarseIterations;
    Film film = start;
    CpuStepper stepper;
    stepper.load(q, film);
    for (const StageSpec& spec : stepStages()) {
      if (spec.stage == Stage::ImplicitVelocity || (stopBeforeSweeps && spec.stage == Stage::VertexBlockDescent)) break;
      if (spec.runs(q, u)) stepper.runStage(spec.stage, u);
    }
    double along = 0, norm = 0;
    for (size_t i = 0; i < film.state.size(); ++i) {
      along += bulge.get(i).dot(film.state.position.get(i) - flat.get(i));
      norm += bulge.get(i).squaredNorm();
    }
    return BulgeResult{along / norm, implicitObjective(q, u, film.topology, film.state)};
  };
  return {solve(6, 0, true), solve(6, 0, false), solve(6, 20, false), solve(400, 20, false)};
}

TEST(CoarseCorrection, SolvesTheFilmWideModeTheSweepsHardlyReach) {
  const BulgeStep b = bulgeStep();
  const double restoring = b.first.amplitude - b.converged.amplitude;  // what the exact step takes back
  const double sweepsLeft = (b.sweepsAlone.amplitude - b.converged.amplitude) / restoring;
  const double coarseLeft = (b.withCoarse.amplitude - b.converged.amplitude) / restoring;
  std::printf(
      "bulge amplitude: first guess %.4f, converged %.4f; 6 sweeps leave %.1f%% of the step's pull-back undone, with "
      "the coarse correction %.1f%%. Objective above the converged one: first %.3e J, sweeps %.3e, coarse %.3e\n",
      b.first.amplitude, b.converged.amplitude, 100 * sweepsLeft, 100 * coarseLeft,
      b.first.objective - b.converged.objective, b.sweepsAlone.objective - b.converged.objective,
      b.withCoarse.objective - b.converged.objective);
  ASSERT_GT(restoring, 0.0) << "the film's tension must pull the bulge back";
  // Measured: 6 sweeps leave 67.3% of the pull-back undone, with the correction 17.3% (the patch system, with a
  // patch moving rigidly, is stiffer than the film's smooth bulge: unsmoothed aggregation under-corrects; 1 to 8
  // rings all leave 20-22% at a quarter-spring patch limit). Bounds: the sweeps leave more than half, the
  // correction less than twice what was measured.
  EXPECT_GT(sweepsLeft, 0.5) << "the test's mode is not one the sweeps miss";
  EXPECT_LT(std::abs(coarseLeft), 0.35) << "the coarse correction did not reach the film-wide mode";
  EXPECT_LT(b.withCoarse.objective, b.sweepsAlone.objective);
}

}  // namespace
}  // namespace gb
