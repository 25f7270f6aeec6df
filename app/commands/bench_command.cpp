#include "app/commands/bench_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app/commands/cli_checks.h"
#include "capture/output_file.h"
#include "capture/scripted_gestures.h"
#include "capture/untrusted.h"
#include "host/backend.h"
#include "host/vulkan_context.h"
#include "simulation/simulation.h"

namespace gb {

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

// Best-of-five STREAM triad a = b + s c over three arrays of 2^24 doubles (384 MiB, far beyond cache),
// both cores; bandwidth counted the STREAM way, 24 bytes per element.
double streamTriadGBs() {
  const long n = 1L << 24;
  std::vector<double> a(static_cast<size_t>(n)), b(static_cast<size_t>(n), 1.0), c(static_cast<size_t>(n), 2.0);
  double best = 1e30;
  for (int run = 0; run < 5; ++run) {
    const auto start = Clock::now();
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i)
      a[static_cast<size_t>(i)] = b[static_cast<size_t>(i)] + 3.0 * c[static_cast<size_t>(i)];
    best = std::min(best, seconds(start));
  }
  return 24.0 * static_cast<double>(n) / best / 1e9;
}

// What one particle-step asks of memory and the FPU, counted from the code of cpu-reference/stages/stages.cpp
// (the shaders are line-by-line ports). s = springs per particle (2 S / N), t = triangles per particle
// (3 T / N). Bytes are those the code loads and stores, whether or not a cache serves them.
struct Cost {
  double bytes = 0;
  double flops = 0;
};

Cost costPerParticleStep(double s, double t) {
  Cost c;
  // geometry, pass 1 per triangle (t/3 of them per particle): 3 indices and 3 positions in, normal and 3
  // corner areas out (72 B), ~100 flops (edges, cross product, norm, three corners' dots and squared norms);
  // pass 2 per triangle visit: triangle id, its 3 indices (to find the corner), normal, corner area (32 B),
  // ~5 flops; per particle 2 offsets, 4 floats out.
  c.bytes += 72 * t / 3 + 32 * t + 24;
  c.flops += 100 * t / 3 + 5 * t + 10;
  // film state: area, liquid, lifetime in; thickness, elasticity, lifetime out; ~10 flops.
  c.bytes += 24;
  c.flops += 10;
  // air inflow: position in, air out; two distances and the weighted sum, ~30 flops.
  c.bytes += 24;
  c.flops += 30;
  // air transfer: own position, boundary flag, 2 offsets, air out; per spring the neighbour id, its air and
  // position (28 B) and ~30 flops (difference, two norms, dot, division, weighted sum).
  c.bytes += 36 + 28 * s;
  c.flops += 10 + 30 * s;
  // forces: position, velocity, normal, air, inflow (60 B), elasticity, area, mass, 2 offsets, force out;
  // per spring neighbour id, spring id, rest length, neighbour position, velocity, elasticity (40 B) and
  // ~40 flops (difference, norm, division, stiffness, stretch, damping projection, two accumulations).
  c.bytes += 92 + 40 * s;
  c.flops += 30 + 40 * s;
  // integrate: alive, boundary, position, velocity, force, mass in; position, velocity out; ~15 flops.
  c.bytes += 72;
  c.flops += 15;
  return c;
}

struct FilmRun {
  nlohmann::json result;
  bool ok = false;
};

FilmRun benchOne(const std::string& backendName, const std::string& device, int particles, int steps,
                 double streamGBs) {
  FilmRun out;
  std::string report;
  std::unique_ptr<Stepper> stepper = makeStepper(backendFromName(backendName), device, report);
  Params params;
  params.particlesAtFullSolution = particles;
  params.maxSubsteps = 1000000;
  GestureOptions g;
  g.start = 0.0f;
  const auto genStart = Clock::now();
  Simulation sim(params, WandTool{}, gestureAt(Gesture::Straight, g, 0.0), std::move(stepper));
  const double generation = seconds(genStart);
  const float dt = params.frameTime / static_cast<float>(sim.substepsPerFrame());
  std::vector<StepUniforms> batch;
  for (int k = 0; k < 8; ++k)
    batch.push_back(sim.uniformsFor(gestureAt(Gesture::Straight, g, 0.1 + static_cast<double>(k) * dt),
                                    gestureAt(Gesture::Straight, g, 0.1 + static_cast<double>(k + 1) * dt), dt));
  // As in a frame: drainage once per frame (here once per batch of 8, a frame of 8 substeps).
  batch.back().drainageDt = params.frameTime;
  Stepper& st = sim.stepper();
  st.run(batch);  // warm-up: first submission, caches
  const auto start = Clock::now();
  int done = 0;
  while (done < steps) {
    st.run(batch);
    done += static_cast<int>(batch.size());
  }
  const double wall = seconds(start);
  st.resetStageTimes();
  st.enableTiming(true);
  st.run(batch);
  st.enableTiming(false);

  const Film& film = sim.film();
  const double n = static_cast<double>(film.state.size());
  const Cost cost = costPerParticleStep(2.0 * static_cast<double>(film.topology.springCount()) / n,
                                        3.0 * static_cast<double>(film.topology.triangleCount()) / n);
  const double stepsPerSecond = done / wall;
  const double particleSteps = stepsPerSecond * n;
  nlohmann::json stages;
  for (int s = 0; s < kStageCount; ++s) stages[stageName(static_cast<Stage>(s))] = st.stageTimes()[s] / 8.0;
  out.result = {{"backend", st.name()},
                {"particles", film.state.size()},
                {"triangles", film.topology.triangleCount()},
                {"springs", film.topology.springCount()},
                {"generation_s", generation},
                {"steps", done},
                {"steps_per_s", stepsPerSecond},
                {"particle_steps_per_s", particleSteps},
                {"stage_ms_per_step", stages},
                {"bytes_per_particle_step", cost.bytes},
                {"flops_per_particle_step", cost.flops},
                {"effective_bandwidth_GBs", particleSteps * cost.bytes / 1e9},
                {"gflops", particleSteps * cost.flops / 1e9},
                {"stream_triad_GBs", streamGBs}};
  std::printf("%-44s %9zu %10.1f %12.2fM %8.2f %8.2f  %s\n", st.name().substr(0, 44).c_str(), film.state.size(),
              stepsPerSecond, particleSteps / 1e6, particleSteps * cost.bytes / 1e9, particleSteps * cost.flops / 1e9,
              [&] {
                std::string s;
                for (int k = 0; k < kStageCount; ++k) {
                  char buf[48];
                  std::snprintf(buf, sizeof buf, "%s=%.3f ", stageName(static_cast<Stage>(k)),
                                st.stageTimes()[k] / 8.0);
                  s += buf;
                }
                return s;
              }()
                  .c_str());
  std::fflush(stdout);
  out.ok = true;
  return out;
}

}  // namespace

CLI::App* addBenchCommand(CLI::App& app, BenchOptions& o) {
  CLI::App* command = app.add_subcommand("bench", "measure step throughput on each backend for several film sizes");
  command->add_option("--sizes", o.sizes, "film sizes in particles")->transform(WholeNumber(100, kMaxParticles));
  command->add_option("--backends", o.backends, "backends to measure")->check(CLI::IsMember({"cpu", "vulkan"}));
  command->add_option("--steps", o.steps, "substeps timed per film")->transform(WholeNumber(8, 100000));
  command->add_option("--json", o.json, "where to write the results (.json)")->check(NotEmpty());
  command->add_option("--device", o.device, "Vulkan device: index or part of its name");
  return command;
}

int runBenchmark(const BenchOptions& o) {
  std::vector<OutputFolder> holds;
  try {  // refused before minutes of measuring, not after
    holds = checkOutputs({{"--json", o.json, Output::Kind::File, ".json"}});
  } catch (const OutputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  std::printf("giantbubble bench: %d substeps per film, sizes", o.steps);
  for (int s : o.sizes) std::printf(" %d", s);
  std::printf("\nmeasuring STREAM triad... ");
  std::fflush(stdout);
  const double stream = streamTriadGBs();
  std::printf("%.2f GB/s\n\n", stream);
  std::printf("%-44s %9s %10s %13s %8s %8s  %s\n", "backend", "particles", "steps/s", "part-steps/s", "GB/s", "GFLOP/s",
              "ms per step by stage");
  nlohmann::json runs = nlohmann::json::array();
  int failures = 0;
  for (const std::string& backend : o.backends)
    for (int size : o.sizes) {
      try {
        runs.push_back(benchOne(backend, o.device, size, o.steps, stream).result);
      } catch (const std::exception& e) {
        std::printf("%-44s %9d  failed: %s\n", backend.c_str(), size, e.what());
        runs.push_back({{"backend", backend}, {"particles", size}, {"error", e.what()}});
        ++failures;
      }
    }
  const nlohmann::json doc = {{"stream_triad_GBs", stream}, {"runs", runs}};
  try {
    writeFileAtomically(o.json, doc.dump(2) + '\n');
  } catch (const OutputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  std::printf("\nresults written to %s\n", printablePath(o.json).c_str());
  return failures ? 1 : 0;
}

}  // namespace gb
