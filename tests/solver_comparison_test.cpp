// The candidate solvers of the implicit step (research/solver_comparison.h) that bench/solver_bench.cpp
// measures: they solve the objective the step solves, and each of them makes progress on it.
#include "research/solver_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "capture/scripted_gestures.h"
#include "simulation/simulation.h"
#include "stages/cpu_stepper.h"

namespace gb {
namespace {

struct Prepared {
  Params params;
  Film film;
  StepUniforms uniforms;
};

// A 600-particle film of the given tension model, 0.3 s into a 2.5 m/s stroke, brought up to the solver (every
// stage before vertex_block_descent).
Prepared preparedFilm(int tensionModel) {
  Prepared out;
  out.params.particlesAtFullSolution = 600;
  out.params.tensionModel = tensionModel;
  GestureOptions g;
  g.start = 0.0f;
  g.speed = 2.5f;
  Simulation sim(out.params, WandTool{}, gestureAt(Gesture::Straight, g, 0.0));
  for (int f = 1; f <= 15; ++f) sim.advanceFrame(gestureAt(Gesture::Straight, g, f * 0.02));
  out.film = sim.film();
  out.uniforms = sim.uniformsFor(gestureAt(Gesture::Straight, g, 0.3), gestureAt(Gesture::Straight, g, 0.32), 0.02f);
  CpuStepper stepper;
  stepper.load(out.params, out.film);
  for (const StageSpec& spec : stepStages()) {
    if (spec.stage == Stage::VertexBlockDescent) break;
    if (spec.runs(out.params, out.uniforms)) stepper.runStage(spec.stage, out.uniforms);
  }
  return out;
}

class SolverComparison : public ::testing::TestWithParam<int> {};

// implicitObjective is the function whose gradient the solvers follow: its central difference in each
// coordinate of a few particles matches objectiveBlock's gradient within 1% of the gradient's norm plus 1e-6 N
// (float32 positions under 1e-4 m steps: ~1e-7 relative rounding of each term). The spring and contact damping are
// off here: the gradient leaves out the derivative of their direction by design (implicit_euler.cpp), which on the
// light physical film moving at 2.5 m/s is a third of its small gradient.
TEST_P(SolverComparison, TheObjectiveHasTheSolversGradient) {
  Prepared in = preparedFilm(GetParam());
  in.params.springDamping = 0.0f;
  in.params.collisionDamping = 0.0f;
  State& s = in.film.state;
  const Topology& topo = in.film.topology;
  constexpr float step = 1e-4f;
  for (size_t k = 0; k < topo.colourOrder.size(); k += topo.colourOrder.size() / 7) {
    const uint32_t i = topo.colourOrder[k];
    const Vec3 gradient = objectiveBlock(in.params, in.uniforms, Bubble{}, topo, s, i).gradient;
    Vec3 difference;
    for (int axis = 0; axis < 3; ++axis) {
      const Vec3 x = s.position.get(i);
      Vec3 plus = x, minus = x;
      plus[axis] += step;
      minus[axis] -= step;
      s.position.set(i, plus);
      const double above = implicitObjective(in.params, in.uniforms, topo, s);
      s.position.set(i, minus);
      const double below = implicitObjective(in.params, in.uniforms, topo, s);
      s.position.set(i, x);
      difference[axis] = static_cast<float>((above - below) / static_cast<double>(plus[axis] - minus[axis]));
    }
    EXPECT_LT((difference - gradient).norm(), 0.01f * gradient.norm() + 1e-6f)
        << "particle " << i << ": difference " << difference.transpose() << ", gradient " << gradient.transpose();
  }
}

// Every candidate makes progress: after 20 iterations the objective is below the first guess's and below its own
// value after one iteration (the first guess is ~1e-3 J above the minimum here; float rounding of the objective is
// ~1e-9 J).
TEST_P(SolverComparison, EveryCandidateLowersTheObjective) {
  const Prepared in = preparedFilm(GetParam());
  const double first = implicitObjective(in.params, in.uniforms, in.film.topology, in.film.state);
  for (const SolverChoice& choice :
       {SolverChoice{SolverKind::VertexBlockDescent}, SolverChoice{SolverKind::VertexBlockDescent, 0.9f},
        SolverChoice{SolverKind::Jacobi, 0.0f, 0.5f}, SolverChoice{SolverKind::Jacobi, 0.9f, 0.5f},
        SolverChoice{SolverKind::NewtonPcg, 0.0f, 1.0f, 10}}) {
    Film film = in.film;
    ImplicitSolve solve(in.params, in.uniforms, film, choice);
    solve.iterate();
    const double one = implicitObjective(in.params, in.uniforms, film.topology, film.state);
    while (solve.iterations() < 20) solve.iterate();
    const double twenty = implicitObjective(in.params, in.uniforms, film.topology, film.state);
    std::printf("%-40s first guess %.6e, 1 iteration %.6e, 20 iterations %.6e J\n", describe(choice).c_str(), first,
                one, twenty);
    EXPECT_LT(twenty, first) << describe(choice);
    EXPECT_LT(twenty, one) << describe(choice);
  }
}

INSTANTIATE_TEST_SUITE_P(Solvers, SolverComparison, ::testing::Values(0, 1),
                         [](const auto& test) { return test.param ? "physical" : "springs"; });

// A closed bubble is refused with a message: its gas term needs the volume at every iterate.
TEST(SolverComparisonInput, AClosedFilmIsRefused) {
  Prepared in = preparedFilm(0);
  in.uniforms.closed = 1;
  EXPECT_THROW(ImplicitSolve(in.params, in.uniforms, in.film, SolverChoice{}), std::invalid_argument);
  EXPECT_THROW(implicitObjective(in.params, in.uniforms, in.film.topology, in.film.state), std::invalid_argument);
}

}  // namespace
}  // namespace gb
