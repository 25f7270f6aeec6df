// Per-stage cost of the CPU step on two-wand films of the sizes in Table 1 and beyond.
// Run: ./build/bench/gb_stage_bench  (counters: particles/s = particle-stages per second)
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "cpu_stepper.h"
#include "scripted_gestures.h"
#include "simulation.h"

namespace gb {
namespace {

// One film per size, built once and shared by every benchmark of that size (generation takes seconds at
// 1M particles). It is first advanced a few frames with moving wands so that air flow and stretch are not
// trivially zero.
struct Fixture {
  Params params;
  std::unique_ptr<Simulation> sim;
  StepUniforms uniforms;
};

Fixture& fixture(int particles) {
  static std::map<int, std::unique_ptr<Fixture>> cache;
  auto& slot = cache[particles];
  if (!slot) {
    slot = std::make_unique<Fixture>();
    slot->params.particlesAtFullSolution = particles;
    slot->params.maxSubsteps = 1000000;
    GestureOptions g;
    g.start = 0.0f;
    slot->sim = std::make_unique<Simulation>(slot->params, WandTool{}, gestureAt(Gesture::Straight, g, 0.0));
    for (int f = 1; f <= 3; ++f) slot->sim->advanceFrame(gestureAt(Gesture::Straight, g, f * 0.02));
    const float dt = slot->params.frameTime / static_cast<float>(slot->sim->substepsPerFrame());
    slot->uniforms = slot->sim->uniformsFor(gestureAt(Gesture::Straight, g, 0.06), gestureAt(Gesture::Straight, g, 0.06 + dt), dt);
  }
  return *slot;
}

template <class Stage>
void runStage(benchmark::State& bench, Stage&& stage) {
  Fixture& fx = fixture(static_cast<int>(bench.range(0)));
  Film& film = fx.sim->film();
  const size_t n = film.state.size();
  for (auto _ : bench) {
    stage(fx, film, n);
    benchmark::ClobberMemory();
  }
  bench.counters["particles/s"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}

template <class Body>
void parallelFor(size_t n, Body&& body) {
  const auto count = static_cast<long>(n);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < count; ++i) body(static_cast<size_t>(i));
}

void BM_Geometry(benchmark::State& b) {
  runStage(b, [](Fixture&, Film& f, size_t n) { parallelFor(n, [&](size_t i) { computeVertexGeometry(f.topology, f.state, i); }); });
}
void BM_FilmState(benchmark::State& b) {
  runStage(b, [](Fixture& fx, Film& f, size_t n) {
    parallelFor(n, [&](size_t i) { updateFilmState(fx.params, 0.0f, f.state, i); });
  });
}
void BM_AirInflow(benchmark::State& b) {
  runStage(b, [](Fixture& fx, Film& f, size_t n) {
    parallelFor(n, [&](size_t i) { computeAirInflow(fx.params, fx.uniforms, f.state, i); });
  });
}
void BM_AirTransfer(benchmark::State& b) {
  runStage(b, [](Fixture& fx, Film& f, size_t n) {
    parallelFor(n, [&](size_t i) { transferAirFlow(fx.params, f.topology, f.state, i); });
  });
}
void BM_Forces(benchmark::State& b) {
  runStage(b, [](Fixture& fx, Film& f, size_t n) {
    parallelFor(n, [&](size_t i) { computeForces(fx.params, fx.uniforms, fx.params.pressureCoefficient, f.topology, f.state, i); });
  });
}
void BM_Volume(benchmark::State& b) {
  CpuStepper stepper;
  runStage(b, [&](Fixture& fx, Film& f, size_t) { benchmark::DoNotOptimize(stepper.volume(f, fx.uniforms.volumeOrigin)); });
}
// The whole step; integration is timed only here because it moves the film.
void BM_FullStep(benchmark::State& b) {
  runStage(b, [&](Fixture& fx, Film&, size_t) { fx.sim->stepper().run(std::span(&fx.uniforms, 1)); });
}

#define GB_SIZES Arg(10000)->Arg(25650)->Arg(100000)->Unit(benchmark::kMicrosecond)->UseRealTime()
BENCHMARK(BM_Geometry)->GB_SIZES;
BENCHMARK(BM_FilmState)->GB_SIZES;
BENCHMARK(BM_AirInflow)->GB_SIZES;
BENCHMARK(BM_AirTransfer)->GB_SIZES;
BENCHMARK(BM_Forces)->GB_SIZES;
BENCHMARK(BM_Volume)->GB_SIZES;
BENCHMARK(BM_FullStep)->GB_SIZES;

}  // namespace
}  // namespace gb

BENCHMARK_MAIN();
