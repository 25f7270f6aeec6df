// The self-collision search (findContacts), the largest part of a frame on two CPU threads (docs/performance.md).
// Run: ./build/bench/gb_contacts_bench
//
// BM_DefaultPerformance/F: the search after frame F of the README's default performance (40: the bag being drawn,
//   80: mid-stroke, the bag at its fastest, 110: the free bubble after the pinch-off, 200: the free bubble in flight,
//   a closed smooth sheet), with the contact list that frame left as the history.
// BM_FlatFilm/N: a film of N particles hanging still on the default loop after one frame (1,000,000: the largest
//   size docs/performance.md measures), where every candidate the cells hold is an in-plane neighbour.
// BM_DefaultPerformanceOnDevice/F, BM_FlatFilmOnDevice/N: the same searches on the Vulkan device
//   (VulkanStepper::findContacts, kernels/contacts/contact_*.comp), the list read back as Simulation has it read back;
//   skipped with a message when there is no device.
// Counters: pairs listed, particles, and ns per particle.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "bench/bench_device.h"
#include "capture/scripted_gestures.h"
#include "host/vulkan_stepper.h"
#include "scene/scene_file.h"
#include "simulation/simulation.h"
#include "topology/collision.h"

namespace gb {
namespace {

struct SearchCase {
  Params params;
  Film film;
  ContactHistory history;
};

SearchCase caseFrom(const Simulation& sim) {
  return {sim.params(), sim.film(), {sim.film().topology.contacts, sim.film().state.size()}};
}

const SearchCase& defaultPerformanceAt(int frame) {
  static std::map<int, SearchCase> cases;
  if (const auto found = cases.find(frame); found != cases.end()) return found->second;
  const Scene scene = resolveScene("default");
  const GestureOptions& stroke = scene.run.gestureOptions;
  Simulation sim(scene.run.params, WandTool{}, gestureAt(Gesture::Giant, stroke, 0.0));
  for (int f = 1; f <= frame; ++f)
    sim.advanceFrame(gestureAt(Gesture::Giant, stroke, static_cast<double>(f) * scene.run.params.frameTime));
  return cases.emplace(frame, caseFrom(sim)).first->second;
}

const SearchCase& flatFilm(int particles) {
  static std::map<int, SearchCase> cases;
  if (const auto found = cases.find(particles); found != cases.end()) return found->second;
  Params params;
  params.particlesAtFullSolution = particles;
  GestureOptions g;
  g.start = 0.0f;
  Simulation sim(params, WandTool{}, gestureAt(Gesture::Straight, g, 0.0));
  sim.advanceFrame(gestureAt(Gesture::Straight, g, 0.0));
  return cases.emplace(particles, caseFrom(sim)).first->second;
}

void countPairs(benchmark::State& state, const Film& film, size_t pairs) {
  const auto particles = static_cast<double>(film.state.size());
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["particles"] = particles;
  state.counters["ns_per_particle"] = benchmark::Counter(particles * static_cast<double>(state.iterations()) * 1e-9,
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The search as Simulation::updateContacts runs it: reach of one frame plus 5 mm of slack, the search's memory kept
// from one frame to the next.
void search(benchmark::State& state, const SearchCase& c) {
  Film film = c.film;
  ContactSearch search;
  size_t pairs = 0;
  for (auto _ : state) pairs = search.find(c.params, c.params.frameTime, 0.005f, film, c.history);
  countPairs(state, film, pairs);
}

// The same search on the device, its room grown by a first search outside the timing, as a running show's is.
void searchOnDevice(benchmark::State& state, const SearchCase& c) {
  const std::shared_ptr<const VulkanContext> device = bench::vulkanDevice();
  if (!device) {
    state.SkipWithError("no Vulkan device");
    return;
  }
  Film film = c.film;
  VulkanStepperOptions onDevice;  // the device search whatever the device (Automatic leaves a CPU driver to the CPU)
  onDevice.contactSearch = WorkPlace::Device;
  VulkanStepper stepper(device, onDevice);
  stepper.load(c.params, film);
  stepper.findContacts(c.params, c.params.frameTime, 0.005f, film, c.history);
  for (auto _ : state) stepper.findContacts(c.params, c.params.frameTime, 0.005f, film, c.history);
  countPairs(state, film, film.topology.contacts[film.state.size()] / 2);
}

void BM_DefaultPerformance(benchmark::State& state) {
  search(state, defaultPerformanceAt(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_DefaultPerformance)->Arg(40)->Arg(80)->Arg(110)->Arg(200)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FlatFilm(benchmark::State& state) { search(state, flatFilm(static_cast<int>(state.range(0)))); }
BENCHMARK(BM_FlatFilm)->Arg(10000)->Arg(25650)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DefaultPerformanceOnDevice(benchmark::State& state) {
  searchOnDevice(state, defaultPerformanceAt(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_DefaultPerformanceOnDevice)
    ->Arg(40)
    ->Arg(80)
    ->Arg(110)
    ->Arg(200)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_FlatFilmOnDevice(benchmark::State& state) { searchOnDevice(state, flatFilm(static_cast<int>(state.range(0)))); }
BENCHMARK(BM_FlatFilmOnDevice)
    ->Arg(10000)
    ->Arg(25650)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace gb

BENCHMARK_MAIN();
