// The renderer's speed: on the paper's largest scene (Table 1: 25,650 particles) and on the README's main job.
// Run: ./build/bench/gb_render_bench   (counter fps = frames per second; docs/performance.md has the figures)
//
// BM_Render/upload:   one frame rendered from the CPU state (uploaded every frame, the CPU backend's path).
// BM_Render/inplace:  one frame rendered from the Vulkan stepper's own buffers (no copy).
// BM_FrameSimulationAndRender: a whole frame as `giantbubble run --render` does it, minus the file output.
// BM_RenderMainJob/F/S: the README's main job's render of its frame F (60: the bag being drawn; 200: the free
//                      bubble), 960x540 at drawn scale S percent (75: 720x405, as `run` draws on a CPU driver), one
//                      sample, pixels read back: the main job's own per-frame render.
// BM_PropsMesh, BM_FilmSwirls, BM_FollowCamera/L/Y: the renderer's CPU work per frame, what bounds it on a real GPU
//                      (the follow camera on a bubble of 10 x 4^L + 2 particles centred Y cm above the floor: at
//                      120 the default pitch holds, at 60 the camera is pitched down to keep above the floor).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "bench/bench_device.h"
#include "capture/scripted_gestures.h"
#include "host/film_swirls.h"
#include "host/render_scene.h"
#include "host/renderer.h"
#include "host/vulkan_context.h"
#include "host/vulkan_stepper.h"
#include "scene/scene_file.h"
#include "simulation/simulation.h"

namespace gb {
namespace {

constexpr int kParticles = 25650;  // Table 1's largest film

using bench::vulkanDevice;

std::unique_ptr<Simulation> largestScene(std::unique_ptr<Stepper> stepper) {
  Params params;
  params.particlesAtFullSolution = kParticles;
  GestureOptions g;
  g.start = 0.0f;
  auto sim = std::make_unique<Simulation>(params, WandTool{}, gestureAt(Gesture::Straight, g, 0.0), std::move(stepper));
  sim->advanceFrame(gestureAt(Gesture::Straight, g, 0.02));  // air flow and curvature are not all zero
  return sim;
}

RenderOptions sized(const benchmark::State& state) {
  RenderOptions o;
  o.width = static_cast<int>(state.range(0));
  o.height = static_cast<int>(state.range(1));
  return o;
}

// CPU seconds used by the whole process so far, every thread (lavapipe's rasteriser threads included). On a
// shared machine wall time depends on the neighbours' load; CPU time per frame does much less, and
// cores / (CPU time per frame) is what the frame rate would be with the cores to ourselves.
double processCpuSeconds() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_utime.tv_sec + r.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(r.ru_utime.tv_usec + r.ru_stime.tv_usec);
}

void report(benchmark::State& state, const Simulation& sim, double cpuAtStart) {
  const double frames = static_cast<double>(state.iterations());
  state.counters["fps"] = benchmark::Counter(frames, benchmark::Counter::kIsRate);
  state.counters["cpu_ms_per_frame"] = 1e3 * (processCpuSeconds() - cpuAtStart) / std::max(frames, 1.0);
  state.counters["particles"] = static_cast<double>(sim.film().state.size());
  state.counters["triangles"] = static_cast<double>(sim.film().topology.triangleCount());
}

RenderFrame frameOf(Simulation& sim, const WireFrame& wire) {
  RenderFrame f;
  f.film = &sim.film();
  f.aerosol = &sim.aerosol();
  f.wireFrame = &wire;
  return f;
}

WireFrame wireOf(const Simulation& sim) {
  GestureOptions g;
  g.start = 0.0f;
  return makeWireFrame(sim.film().tool, gestureAt(Gesture::Straight, g, sim.time()), sim.film().stringLength,
                       Vec3(0.0f, -9.81f, 0.0f));
}

void BM_Render(benchmark::State& state, bool inPlace) {
  const auto device = vulkanDevice();
  if (!device) return state.SkipWithError("no Vulkan device");
  std::unique_ptr<Stepper> stepper;
  if (inPlace) stepper = std::make_unique<VulkanStepper>(device);
  auto sim = largestScene(std::move(stepper));
  Renderer renderer(device, sized(state), studioEnvironment());
  const WireFrame wire = wireOf(*sim);
  RenderFrame frame = frameOf(*sim, wire);
  DeviceFilm onDevice;
  if (inPlace) {
    onDevice = dynamic_cast<VulkanStepper&>(sim->stepper()).deviceFilm();
    frame.deviceFilm = &onDevice;
  }
  const double cpu = processCpuSeconds();
  for (auto _ : state) renderer.render(frame, false);
  report(state, *sim, cpu);
}
BENCHMARK_CAPTURE(BM_Render, upload, false)
    ->Args({960, 540})  // the README's main job
    ->Args({1280, 720})
    ->Args({1920, 1080})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Render, inplace, true)->Args({1280, 720})->Unit(benchmark::kMillisecond)->UseRealTime();

// A whole frame as `giantbubble run --render` does it, minus the file output: the simulation's frame (one
// implicit step), then the render with the pixels read back.
void BM_FrameSimulationAndRender(benchmark::State& state) {
  const auto device = vulkanDevice();
  if (!device) return state.SkipWithError("no Vulkan device");
  auto sim = largestScene(nullptr);
  Renderer renderer(device, sized(state), studioEnvironment());
  GestureOptions g;
  g.start = 0.0f;
  const double cpu = processCpuSeconds();
  for (auto _ : state) {
    sim->advanceFrame(gestureAt(Gesture::Straight, g, sim->time() + 0.02));
    const WireFrame wire = wireOf(*sim);
    renderer.render(frameOf(*sim, wire), true);
    benchmark::DoNotOptimize(renderer.readPixels());
  }
  report(state, *sim, cpu);
}
BENCHMARK(BM_FrameSimulationAndRender)->Args({1280, 720})->Unit(benchmark::kMillisecond)->UseRealTime();

// The default performance after `frame` frames, with the camera framing it as the main job's does.
struct MainJobFrame {
  std::unique_ptr<Simulation> sim;
  WireFrame wire;
  OrbitCamera camera;
};

MainJobFrame mainJobAt(int frame, float aspect) {
  const Scene scene = resolveScene("default");
  const GestureOptions& stroke = scene.run.gestureOptions;
  const double h = scene.run.params.frameTime;
  MainJobFrame m;
  m.sim = std::make_unique<Simulation>(scene.run.params, WandTool{}, gestureAt(Gesture::Giant, stroke, 0.0));
  FilmFraming::Options framingOptions;
  framingOptions.aspect = aspect;
  FilmFraming framing(framingOptions);
  for (int f = 1; f <= frame; ++f) {
    m.sim->advanceFrame(gestureAt(Gesture::Giant, stroke, f * h));
    m.camera = framing.update(OrbitCamera{}, m.sim->film().state, static_cast<float>(h));
  }
  m.wire = m.sim->wireFrame(gestureAt(Gesture::Giant, stroke, frame * h));
  return m;
}

void BM_RenderMainJob(benchmark::State& state) {
  const auto device = vulkanDevice();
  if (!device) return state.SkipWithError("no Vulkan device");
  RenderOptions options;
  const float scale = 0.01f * static_cast<float>(state.range(1));
  options.width = static_cast<int>(std::lround(960.0f * scale));
  options.height = static_cast<int>(std::lround(540.0f * scale));
  options.samples = 1;
  MainJobFrame m = mainJobAt(static_cast<int>(state.range(0)), 960.0f / 540.0f);
  Renderer renderer(device, options, skyEnvironment());  // the main job's
  RenderFrame frame = frameOf(*m.sim, m.wire);
  frame.aerosolLifetime = m.sim->params().aerosolLifetime;
  frame.camera = m.camera;
  const double cpu = processCpuSeconds();
  for (auto _ : state) {
    renderer.render(frame, true);
    benchmark::DoNotOptimize(renderer.readPixels());
  }
  report(state, *m.sim, cpu);
}
BENCHMARK(BM_RenderMainJob)
    ->Args({60, 100})
    ->Args({60, 75})
    ->Args({200, 100})
    ->Args({200, 75})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The renderer's own CPU work per frame, no Vulkan: the props mesh (floor, string, sticks, the rims of holes)
// and the film's swirl factors. On a real GPU this, not the GPU, bounds the render's frame rate.
void BM_PropsMesh(benchmark::State& state) {
  auto sim = largestScene(nullptr);
  const WireFrame wire = wireOf(*sim);
  for (auto _ : state) benchmark::DoNotOptimize(buildProps(&wire, &sim->film()).data());
}
BENCHMARK(BM_PropsMesh)->Unit(benchmark::kMillisecond);

void BM_FilmSwirls(benchmark::State& state) {
  auto sim = largestScene(nullptr);
  FilmSwirls swirls;
  for (auto _ : state) benchmark::DoNotOptimize(swirls.update(sim->film().state).data());
}
BENCHMARK(BM_FilmSwirls)->Unit(benchmark::kMillisecond);

void BM_FollowCamera(benchmark::State& state) {
  const float height = 0.01f * static_cast<float>(state.range(1));
  const Film bubble = generateSphere(Params{}, Vec3(0.0f, height, 0.0f), 0.5f, static_cast<int>(state.range(0)));
  FilmFraming framing;
  for (auto _ : state) benchmark::DoNotOptimize(framing.update(OrbitCamera{}, bubble.state, 0.02f).distance);
  state.counters["particles"] = static_cast<double>(bubble.state.size());
}
BENCHMARK(BM_FollowCamera)->Args({5, 120})->Args({7, 120})->Args({7, 60})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gb

BENCHMARK_MAIN();
