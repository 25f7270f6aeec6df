// The frame's statistics (Simulation::stats): summed on the CPU from the film in host memory, and on the Vulkan
// device (VulkanStepper::probeFilm, a few floats read back). Both also bring the film's geometry in host memory up to
// date, which the outputs read (Simulation::stats says why).
// Run: ./build/bench/gb_statistics_bench
//
// BM_StatisticsOnCpu/N, BM_StatisticsOnDevice/N: a film of N particles hanging on the default loop after one frame;
// the device ones skipped with a message when there is no device.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "bench/bench_device.h"
#include "capture/scripted_gestures.h"
#include "host/vulkan_stepper.h"
#include "simulation/simulation.h"

namespace gb {
namespace {

std::unique_ptr<Simulation> hangingFilm(int particles, std::unique_ptr<Stepper> stepper) {
  Params params;
  params.particlesAtFullSolution = particles;
  GestureOptions g;
  g.start = 0.0f;
  auto sim = std::make_unique<Simulation>(params, WandTool{}, gestureAt(Gesture::Straight, g, 0.0), std::move(stepper));
  sim->advanceFrame(gestureAt(Gesture::Straight, g, 0.0));
  return sim;
}

void measure(benchmark::State& state, Simulation& sim) {
  double area = 0;
  for (auto _ : state) area = sim.stats().area;
  state.counters["particles"] = static_cast<double>(sim.film().state.size());
  state.counters["area_m2"] = area;
}

void BM_StatisticsOnCpu(benchmark::State& state) {
  const auto sim = hangingFilm(static_cast<int>(state.range(0)), nullptr);
  measure(state, *sim);
}
BENCHMARK(BM_StatisticsOnCpu)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_StatisticsOnDevice(benchmark::State& state) {
  const std::shared_ptr<const VulkanContext> device = bench::vulkanDevice();
  if (!device) {
    state.SkipWithError("no Vulkan device");
    return;
  }
  VulkanStepperOptions onDevice;  // the device's sums whatever the device (Automatic leaves a CPU driver to the CPU)
  onDevice.statistics = WorkPlace::Device;
  const auto sim = hangingFilm(static_cast<int>(state.range(0)), std::make_unique<VulkanStepper>(device, onDevice));
  measure(state, *sim);
}
BENCHMARK(BM_StatisticsOnDevice)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace gb

BENCHMARK_MAIN();
