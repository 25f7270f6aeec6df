// Per-stage cost on both backends, on two-wand films of the sizes in Table 1 and beyond.
// Run: ./build/bench/gb_stage_bench   (counter particles/s = particle-stages per second)
// CPU stages are timed on the host around runStage; Vulkan stages with GPU timestamp queries over a batch
// of substeps (each stage alone between barriers), so submission overhead is not counted per stage. The
// full step is timed on the host around run() for both: that figure includes everything.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>

#include "bench/bench_device.h"
#include "capture/scripted_gestures.h"
#include "host/vulkan_context.h"
#include "host/vulkan_stepper.h"
#include "simulation/simulation.h"
#include "stages/cpu_stepper.h"

namespace gb {
namespace {

enum class BackendKind { Cpu = 0, Vulkan = 1 };

using bench::vulkanDevice;

// One film per (backend, size), built once: generation takes seconds at large sizes. It is advanced a few
// frames with moving wands so that air flow and stretch are not trivially zero.
struct Fixture {
  Params params;
  std::unique_ptr<Simulation> sim;
  StepUniforms uniforms;
};

Fixture* fixture(BackendKind backend, int particles) {
  static std::map<std::pair<int, int>, std::unique_ptr<Fixture>> cache;
  auto& slot = cache[{static_cast<int>(backend), particles}];
  if (!slot) {
    std::unique_ptr<Stepper> stepper;
    if (backend == BackendKind::Vulkan) {
      if (!vulkanDevice()) return nullptr;
      stepper = std::make_unique<VulkanStepper>(vulkanDevice());
    }
    slot = std::make_unique<Fixture>();
    slot->params.particlesAtFullSolution = particles;
    slot->params.maxSubsteps = 1000000;
    slot->params.frameTime = 0.002f;  // a few substeps per frame: the warm-up stays short at any size
    GestureOptions g;
    g.start = 0.0f;
    slot->sim = std::make_unique<Simulation>(slot->params, WandTool{}, gestureAt(Gesture::Straight, g, 0.0),
                                             std::move(stepper));
    for (int f = 1; f <= 3; ++f) slot->sim->advanceFrame(gestureAt(Gesture::Straight, g, f * 0.002));
    const float dt = slot->params.frameTime / static_cast<float>(slot->sim->substepsPerFrame());
    slot->uniforms =
        slot->sim->uniformsFor(gestureAt(Gesture::Straight, g, 0.006), gestureAt(Gesture::Straight, g, 0.006 + dt), dt);
  }
  return slot.get();
}

void setRate(benchmark::State& bench, size_t particles) {
  bench.counters["particles/s"] =
      benchmark::Counter(static_cast<double>(particles), benchmark::Counter::kIsIterationInvariantRate);
}

// Args: particles, stage. Host time around runStage.
void BM_CpuStage(benchmark::State& bench) {
  Fixture* fx = fixture(BackendKind::Cpu, static_cast<int>(bench.range(0)));
  const auto stage = static_cast<Stage>(bench.range(1));
  StepUniforms u = fx->uniforms;
  u.closed = stage == Stage::Volume ? 1u : 0u;  // the volume runs only for closed films
  for (auto _ : bench) fx->sim->stepper().runStage(stage, u);
  setRate(bench, fx->sim->film().state.size());
  bench.SetLabel(std::string("cpu ") + stageName(stage));
}

// Args: particles. Every stage's GPU time per substep from timestamp queries, as counters (us), over
// batches of 8 substeps of a closed-film step (so the volume reduction is included).
void BM_VulkanStages(benchmark::State& bench) {
  Fixture* fx = fixture(BackendKind::Vulkan, static_cast<int>(bench.range(0)));
  if (!fx) return bench.SkipWithError("no Vulkan device");
  constexpr int kBatch = 8;
  StepUniforms u = fx->uniforms;
  u.closed = 1u;
  u.drainageDt = u.dt;  // time drainage in every substep here (a frame runs it once)
  const std::vector<StepUniforms> batch(kBatch, u);
  Stepper& stepper = fx->sim->stepper();
  stepper.resetStageTimes();
  stepper.enableTiming(true);
  long batches = 0;
  for (auto _ : bench) {
    stepper.run(batch);
    ++batches;
  }
  stepper.enableTiming(false);
  for (int s = 0; s < kStageCount; ++s)
    bench.counters[stageName(static_cast<Stage>(s))] =
        1e3 * stepper.stageTimes()[s] / static_cast<double>(std::max(1L, batches) * kBatch);  // us per substep
  bench.SetLabel("vulkan, GPU us per stage per substep");
}

// Args: backend, particles. A batch of 8 substeps per iteration, as a frame would submit them.
void BM_FullStep(benchmark::State& bench) {
  const auto backend = static_cast<BackendKind>(bench.range(0));
  Fixture* fx = fixture(backend, static_cast<int>(bench.range(1)));
  if (!fx) return bench.SkipWithError("no Vulkan device");
  constexpr int kBatch = 8;
  std::vector<StepUniforms> batch(kBatch, fx->uniforms);
  batch.back().drainageDt = fx->params.frameTime;  // as in a frame: drainage after the last substep
  for (auto _ : bench) fx->sim->stepper().run(batch);
  bench.counters["particles/s"] = benchmark::Counter(static_cast<double>(fx->sim->film().state.size()) * kBatch,
                                                     benchmark::Counter::kIsIterationInvariantRate);
  bench.counters["steps/s"] = benchmark::Counter(kBatch, benchmark::Counter::kIsIterationInvariantRate);
  bench.SetLabel(backend == BackendKind::Cpu ? "cpu" : "vulkan");
}

void stageArgs(benchmark::internal::Benchmark* b) {
  for (int particles : {10000, 25650, 100000})
    for (int stage = 0; stage < kStageCount; ++stage) b->Args({particles, stage});
}
void stepArgs(benchmark::internal::Benchmark* b) {
  for (int backend : {0, 1})
    for (int particles : {10000, 25650, 100000}) b->Args({backend, particles});
}

BENCHMARK(BM_CpuStage)->Apply(stageArgs)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_VulkanStages)->Arg(10000)->Arg(25650)->Arg(100000)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FullStep)->Apply(stepArgs)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace gb

BENCHMARK_MAIN();
