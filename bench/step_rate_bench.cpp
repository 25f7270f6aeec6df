// Implicit frames per second of one film on the CPU backend (docs/performance.md's figures for the physical tension
// model and for 1,000,000 particles): the straight stroke is started at once and run for a few frames so the wands
// move, then the program times (1) the stepper alone, one implicit step of h = 0.02 s at a time on the moving
// wands' uniforms, and (2) whole frames (Simulation::advanceFrame: the step plus the per-frame contact search,
// film growth and burst checks). Per-stage milliseconds of the stepper come from its host timer. Each part also
// prints the calling thread's CPU milliseconds per step (frame), least and median: with OMP_NUM_THREADS=1 that is
// the whole CPU cost, which a busy machine changes far less than the wall clock.
//
// Run: ./build/bench/gb_step_rate_bench [--particles N] [--tension-model 0|1] [--frames N] [--sweeps N] [--coarse N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "capture/scripted_gestures.h"
#include "simulation/simulation.h"

namespace {

using namespace gb;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

double threadCpuMilliseconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// Runs body `count` times; returns the calling thread's CPU milliseconds of each run, sorted.
template <class Body>
std::vector<double> cpuMillisecondsOf(int count, Body&& body) {
  std::vector<double> ms;
  for (int k = 0; k < count; ++k) {
    const double start = threadCpuMilliseconds();
    body();
    ms.push_back(threadCpuMilliseconds() - start);
  }
  std::sort(ms.begin(), ms.end());
  return ms;
}

void printCpu(const char* per, const std::vector<double>& ms) {
  std::printf("  main thread's CPU ms per %s: least %.2f, median %.2f\n", per, ms.front(), ms[ms.size() / 2]);
}

void printStageTimes(const Stepper& stepper, int steps) {
  for (int s = 0; s < kStageCount; ++s)
    if (stepper.stageTimes()[s] > 0)
      std::printf(" %s %.2f", stageName(static_cast<Stage>(s)), stepper.stageTimes()[s] / steps);
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  Params p;
  int frames = 20;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string flag = argv[k];
    const int value = static_cast<int>(std::strtol(argv[k + 1], nullptr, 10));
    if (flag == "--particles")
      p.particlesAtFullSolution = value;
    else if (flag == "--tension-model")
      p.tensionModel = value;
    else if (flag == "--frames")
      frames = value;
    else if (flag == "--sweeps")
      p.solverSweeps = value;
    else if (flag == "--coarse")
      p.coarseIterations = value;
    else if (flag == "--budget")
      p.energyBudget = value;
    else {
      std::fprintf(stderr,
                   "unknown option %s (--particles N --tension-model 0|1 --frames N --sweeps N --coarse N --budget "
                   "0|1)\n",
                   flag.c_str());
      return 2;
    }
  }
  if (!validate(p).empty() || frames < 1) {
    std::fprintf(stderr, "bad options: %s\n", validate(p).empty() ? "--frames < 1" : validate(p).front().c_str());
    return 2;
  }
  GestureOptions g;
  g.start = 0.0f;
  const auto wandsAt = [&](int frame) {
    return gestureAt(Gesture::Straight, g, frame * static_cast<double>(p.frameTime));
  };
  auto t0 = Clock::now();
  Simulation sim(p, WandTool{}, wandsAt(0));
  std::printf("%zu particles, %s tension, %d sweeps: film made in %.1f s\n", sim.film().state.size(),
              p.tensionModel ? "physical" : "springs", p.solverSweeps, secondsSince(t0));
  int frame = 0;
  while (frame < 5) sim.advanceFrame(wandsAt(++frame));  // the wands are moving

  Stepper& stepper = sim.stepper();
  const StepUniforms u = sim.uniformsFor(wandsAt(frame), wandsAt(frame + 1), p.frameTime);
  stepper.resetStageTimes();
  stepper.enableTiming(true);
  t0 = Clock::now();
  const std::vector<double> stepCpu = cpuMillisecondsOf(frames, [&] { stepper.run(std::span(&u, 1)); });
  const double stepSeconds = secondsSince(t0);
  stepper.enableTiming(false);
  std::printf("stepper alone: %.2f frames/s (%.1f ms per step); ms per step by stage:", frames / stepSeconds,
              1e3 * stepSeconds / frames);
  printStageTimes(stepper, frames);
  printCpu("step", stepCpu);

  stepper.resetStageTimes();
  stepper.enableTiming(true);
  t0 = Clock::now();
  const std::vector<double> frameCpu = cpuMillisecondsOf(frames, [&] { sim.advanceFrame(wandsAt(++frame)); });
  const double frameSeconds = secondsSince(t0);
  std::printf("whole frames: %.2f frames/s (%.1f ms per frame)\n", frames / frameSeconds, 1e3 * frameSeconds / frames);
  stepper.enableTiming(false);
  std::printf(
      "  the step's stages in them (drainage runs once a frame, geometry only after the positions changed), ms "
      "per frame:");
  printStageTimes(stepper, frames);
  printCpu("frame", frameCpu);
  return 0;
}
