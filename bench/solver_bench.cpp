// The implicit step's solver, chosen by measurement (docs/model.md "Why vertex block descent"): vertex block
// descent against Chebyshev-accelerated VBD, Chebyshev-accelerated block Jacobi and Newton with matrix-free
// preconditioned conjugate gradients (research/solver_comparison.h), on one step of two films: the default
// film mid-stroke (the default run at 1.5 s, wands moving at 0.6 m/s) and fig11b's 25,650-particle ring film
// at 1.5 s. For each candidate it prints the objective above the best one found (J) and the gradient norm (N)
// after 1, 2, 4, 6, 10, 20 and 50 iterations, and the CPU milliseconds per iteration (best of seven runs of
// ten, the candidates taking turns); then VBD's milliseconds per sweep on the Vulkan backend from its GPU timestamps
// (the other candidates are CPU-only).
//
// Run: ./build/bench/gb_solver_bench [--quick | --fig11b]   (--quick: the default film only, no Vulkan;
// --fig11b: fig11b only)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_device.h"
#include "capture/scripted_gestures.h"
#include "host/vulkan_stepper.h"
#include "research/solver_comparison.h"
#include "scene/scene_file.h"
#include "simulation/simulation.h"
#include "stages/cpu_stepper.h"

namespace {

using namespace gb;
using Clock = std::chrono::steady_clock;

constexpr int kCheckpoints[] = {1, 2, 4, 6, 10, 20, 50};
constexpr double kStateTime = 1.5;          // s into the run: the wands are moving
constexpr int kReferenceIterations = 1000;  // the long runs that give the reference minimum

struct Case {
  const char* name;
  Params params;
  WandTool tool;
  GestureOptions gesture;
};

// A film at kStateTime of its run, and the uniforms of the step that follows.
struct Snapshot {
  Film film;
  StepUniforms uniforms;
};

Snapshot snapshotOf(const Case& c) {
  const auto wandsAt = [&](double t) { return gestureAt(Gesture::Straight, c.gesture, t); };
  Simulation sim(c.params, c.tool, wandsAt(0.0));
  const int frames = static_cast<int>(std::lround(kStateTime / c.params.frameTime));
  for (int f = 1; f <= frames; ++f) sim.advanceFrame(wandsAt(f * static_cast<double>(c.params.frameTime)));
  const double t = frames * static_cast<double>(c.params.frameTime);
  return {sim.film(), sim.uniformsFor(wandsAt(t), wandsAt(t + c.params.frameTime), c.params.frameTime)};
}

// The snapshot brought up to the solver: every stage of the step before vertex_block_descent.
Film prepared(const Params& p, const Snapshot& snap) {
  Film film = snap.film;
  CpuStepper stepper;
  stepper.load(p, film);
  for (const StageSpec& spec : stepStages()) {
    if (spec.stage == Stage::VertexBlockDescent) break;
    if (spec.runs(p, snap.uniforms)) stepper.runStage(spec.stage, snap.uniforms);
  }
  return film;
}

struct Trace {
  std::vector<double> objective, residual;  // after 1..iterations
};

Trace trace(const Params& p, const StepUniforms& u, const Film& start, const SolverChoice& choice, int iterations) {
  Film film = start;
  ImplicitSolve solve(p, u, film, choice);
  Trace t;
  for (int k = 1; k <= iterations; ++k) {
    solve.iterate();
    if (std::find(std::begin(kCheckpoints), std::end(kCheckpoints), k) != std::end(kCheckpoints) || k == iterations) {
      t.objective.push_back(implicitObjective(p, u, film.topology, film.state));
      t.residual.push_back(implicitResidual(p, u, Bubble{}, film.topology, film.state));
    }
  }
  return t;
}

// Milliseconds per iteration of each choice: the best of seven runs of ten iterations from the prepared film,
// the choices taking turns so that a change in the machine's load falls on all of them alike.
std::vector<double> msPerIteration(const Params& p, const StepUniforms& u, const Film& start,
                                   const std::vector<SolverChoice>& choices) {
  std::vector<double> best(choices.size(), 1e30);
  for (int run = 0; run < 7; ++run)
    for (size_t c = 0; c < choices.size(); ++c) {
      Film film = start;
      ImplicitSolve solve(p, u, film, choices[c]);
      const auto t0 = Clock::now();
      for (int k = 0; k < 10; ++k) solve.iterate();
      best[c] = std::min(best[c], std::chrono::duration<double, std::milli>(Clock::now() - t0).count() / 10.0);
    }
  return best;
}

// The spectral radius of a plain iteration, from how fast its gradient norm falls between iterations 10 and 30.
double estimatedRho(const Params& p, const StepUniforms& u, const Film& start, SolverChoice plain) {
  Film film = start;
  ImplicitSolve solve(p, u, film, plain);
  double r10 = 0;
  for (int k = 1; k <= 30; ++k) {
    solve.iterate();
    if (k == 10) r10 = implicitResidual(p, u, Bubble{}, film.topology, film.state);
  }
  const double r30 = implicitResidual(p, u, Bubble{}, film.topology, film.state);
  return std::clamp(std::pow(r30 / r10, 1.0 / 20.0), 0.0, 0.999);
}

void vulkanVbd(const Case& c, const Snapshot& snap) {
  std::shared_ptr<const VulkanContext> device = bench::vulkanDevice();
  if (!device) return;
  VulkanStepper stepper(device);
  for (int sweeps : {1, 6, 10}) {
    Film film = snap.film;
    stepper.load(c.params, film);
    StepUniforms u = snap.uniforms;
    u.solverSweeps = sweeps;
    stepper.run(std::span(&u, 1));  // warm-up
    double best = 1e30;
    for (int run = 0; run < 3; ++run) {
      stepper.resetStageTimes();
      stepper.enableTiming(true);
      stepper.run(std::span(&u, 1));
      stepper.enableTiming(false);
      best = std::min(best, stepper.stageTimes()[static_cast<int>(Stage::VertexBlockDescent)]);
    }
    std::printf("  vulkan (%s): %2d sweeps %8.2f ms, %.2f ms per sweep\n", device->info().name.c_str(), sweeps, best,
                best / sweeps);
  }
}

void runCase(const Case& c, bool vulkan) {
  const auto t0 = Clock::now();
  const Snapshot snap = snapshotOf(c);
  const Params& p = c.params;
  const Film start = prepared(p, snap);
  const StepUniforms& u = snap.uniforms;
  std::printf("\n%s: %zu particles, %zu colours, state at %.2f s (%.1f s to make)\n", c.name, start.state.size(),
              start.topology.colourOffset.size() - 1, kStateTime,
              std::chrono::duration<double>(Clock::now() - t0).count());

  const double rhoVbd = estimatedRho(p, u, start, {SolverKind::VertexBlockDescent});
  const double rhoJacobi = estimatedRho(p, u, start, {SolverKind::Jacobi, 0.0f, 0.5f});
  std::printf("estimated rho: VBD %.4f, Jacobi (relax 0.5) %.4f\n", rhoVbd, rhoJacobi);
  std::vector<SolverChoice> choices = {
      {SolverKind::VertexBlockDescent},
      {SolverKind::VertexBlockDescent, 0.8f},
      {SolverKind::VertexBlockDescent, 0.9f},
      {SolverKind::VertexBlockDescent, 0.95f},
      {SolverKind::VertexBlockDescent, static_cast<float>(rhoVbd)},
      {SolverKind::Jacobi, 0.0f, 0.5f},
      {SolverKind::Jacobi, 0.0f, 1.0f},
      {SolverKind::Jacobi, 0.9f, 0.5f},
      {SolverKind::Jacobi, static_cast<float>(rhoJacobi), 0.5f},
      {SolverKind::NewtonPcg, 0.0f, 1.0f, 5},
      {SolverKind::NewtonPcg, 0.0f, 1.0f, 10},
      {SolverKind::NewtonPcg, 0.0f, 1.0f, 25},
  };

  // The reference minimum: the lowest objective of long runs of accelerated VBD and Newton-PCG.
  const double initial = implicitObjective(p, u, start.topology, start.state);
  double best = initial;
  for (const SolverChoice& longRun : {SolverChoice{SolverKind::VertexBlockDescent, static_cast<float>(rhoVbd)},
                                      SolverChoice{SolverKind::NewtonPcg, 0.0f, 1.0f, 25}})
    best = std::min(best, trace(p, u, start, longRun, kReferenceIterations).objective.back());
  std::printf(
      "objective at the first guess %.6e J; reference minimum (%d iterations of Chebyshev VBD and of "
      "Newton-PCG) %.6e J\n",
      initial, kReferenceIterations, best);
  std::printf("first guess: above the minimum %.3e J, gradient %.3e N\n", initial - best,
              implicitResidual(p, u, Bubble{}, start.topology, start.state));
  std::printf("%-40s %9s", "solver (objective above the minimum, J)", "ms/iter");
  for (int k : kCheckpoints) std::printf(" %9d", k);
  std::printf("\n");
  std::vector<Trace> traces;
  const std::vector<double> ms = msPerIteration(p, u, start, choices);
  for (size_t n = 0; n < choices.size(); ++n) {
    const Trace t = trace(p, u, start, choices[n], 50);
    traces.push_back(t);
    std::printf("%-40s %9.3f", describe(choices[n]).c_str(), ms[n]);
    for (double e : t.objective) std::printf(" %9.2e", e - best);
    std::printf("\n");
    std::fflush(stdout);
  }
  std::printf("%-40s %9s\n", "solver (gradient norm, N)", "");
  for (size_t k = 0; k < choices.size(); ++k) {
    std::printf("%-40s %9s", describe(choices[k]).c_str(), "");
    for (double r : traces[k].residual) std::printf(" %9.2e", r);
    std::printf("\n");
  }
  if (vulkan) vulkanVbd(c, snap);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string only = argc > 1 ? argv[1] : "";
  if (!only.empty() && only != "--quick" && only != "--fig11b") {
    std::fprintf(stderr, "usage: gb_solver_bench [--quick | --fig11b]\n");
    return 2;
  }
  if (only != "--fig11b") {
    const Case defaultFilm{"default film (9,500 particles, straight stroke)", Params{}, WandTool{}, GestureOptions{}};
    runCase(defaultFilm, only.empty());
  }
  if (only == "--quick") return 0;
  const Scene fig11b = builtinScene("fig11b");
  const Case ring{"fig11b (25,650 particles, ring)", fig11b.run.params, fig11b.run.tool, fig11b.run.gestureOptions};
  runCase(ring, true);
  return 0;
}
