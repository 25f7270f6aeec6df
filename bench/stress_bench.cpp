// Stress command for the implicit step (issue 12): random wand motion at h = 0.02 s for many frames on a large
// film, with pokes, pinch-offs and re-dips, as tests/implicit_step_test.cpp's RandomAbuse does at 1,000
// particles. It checks each frame for an instability stop or a non-finite particle, and over every quiet rest
// of the wands (no burst, no event; frames 10-49 of a rest, after the pushed air has passed) that the film's
// mechanical energy (kinetic, gravity, and the springs' energy or 2 gamma x area) does not grow by more than
// 2% of itself (drainage shifts the elasticity by less than that over a second). Prints the counts, the
// largest growth seen and the wall time per frame; exits 1 on any failure.
//
// Run (minutes: under nice):
//   nice -n 19 ./build/bench/gb_stress_bench --particles 25650 --frames 10000 [--tension-model 1] [--seed N]
//   nice -n 19 ./build/bench/gb_stress_bench --particles 100000 --frames 1000
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "implicit_euler.h"
#include "scripted_gestures.h"
#include "simulation.h"

namespace {

using namespace gb;

struct Options {
  int particles = 25650;
  int frames = 10000;
  int tensionModel = 0;
  unsigned seed = 42;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string flag = argv[k];
    const long value = std::strtol(argv[k + 1], nullptr, 10);
    if (flag == "--particles")
      o.particles = static_cast<int>(value);
    else if (flag == "--frames")
      o.frames = static_cast<int>(value);
    else if (flag == "--tension-model")
      o.tensionModel = static_cast<int>(value);
    else if (flag == "--seed")
      o.seed = static_cast<unsigned>(value);
    else {
      std::fprintf(stderr, "unknown option %s (--particles N --frames N --tension-model 0|1 --seed N)\n", flag.c_str());
      std::exit(2);
    }
  }
  if (o.particles < 100 || o.frames < 1 || (o.tensionModel != 0 && o.tensionModel != 1)) {
    std::fprintf(stderr, "need --particles >= 100, --frames >= 1, --tension-model 0 or 1\n");
    std::exit(2);
  }
  return o;
}

// Kinetic + gravity + the tension's energy (springs of Eq. 3, or 2 gamma x area in the physical model), J.
double mechanicalEnergy(Simulation& sim) {
  const FrameStats st = sim.stats();
  const double moving = st.kineticEnergy + st.potentialEnergy;
  if (sim.params().tensionModel == 0) return moving + st.elasticEnergy;
  const Film& film = sim.film();
  double surface = 0;
  for (size_t t = 0; t < film.topology.triangleCount(); ++t)
    surface += triangleTension(film.state, &film.topology.triangles[3 * t]) * 0.5 *
               film.state.triangleNormal.get(t).cast<double>().norm();
  return moving + surface;
}

// The wands: 50 frames of a random straight motion (up to 6 m/s per tip, bouncing off the walls of a 3 m box
// above the floor), then 50 frames at rest, over and over.
class RandomWands {
 public:
  RandomWands(unsigned seed, const WandState& start) : rng_(seed), wands_(start) {}
  static bool resting(int frame) { return (frame / 50) % 2 == 1; }
  [[nodiscard]] const WandState& current() const { return wands_; }
  const WandState& next(int frame, float h) {
    if (frame % 50 == 0 && !resting(frame)) {
      velocity_[0] = randomVelocity();
      velocity_[1] = randomVelocity();
    }
    WandState n = wands_;
    Vec3* tips[2] = {&n.leftPosition, &n.rightPosition};
    for (int k = 0; k < 2 && !resting(frame); ++k) {
      const Vec3 before = *tips[k];
      *tips[k] = (before + h * velocity_[k]).cwiseMax(Vec3(-1.5f, 0.3f, -1.5f)).cwiseMin(Vec3(1.5f, 2.5f, 1.5f));
      if ((*tips[k] - before).norm() < 1e-6f) velocity_[k] = -velocity_[k];
    }
    n.leftVelocity = (n.leftPosition - wands_.leftPosition) / h;
    n.rightVelocity = (n.rightPosition - wands_.rightPosition) / h;
    wands_ = n;
    return wands_;
  }

 private:
  Vec3 randomVelocity() {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    return 6.0f * Vec3(unit(rng_), unit(rng_), unit(rng_)) / std::sqrt(3.0f);
  }
  std::mt19937 rng_;
  WandState wands_;
  Vec3 velocity_[2] = {Vec3::Zero(), Vec3::Zero()};
};

bool allFinite(const State& s) {
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i] && !(s.position.get(i).allFinite() && s.velocity.get(i).allFinite())) return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  Params p;
  p.particlesAtFullSolution = o.particles;
  p.tensionModel = o.tensionModel;
  RandomWands wands(o.seed, gestureAt(Gesture::Straight, GestureOptions{}, 0.0));
  Simulation sim(p, WandTool{}, gestureAt(Gesture::Straight, GestureOptions{}, 0.0));
  std::printf("stress: %zu particles, %s tension, %d frames of random wand motion (seed %u)\n", sim.film().state.size(),
              o.tensionModel ? "physical" : "springs", o.frames, o.seed);
  std::fflush(stdout);
  int pokes = 0, pinches = 0, dips = 0, restsChecked = 0, failures = 0;
  double worstGrowth = -1e30, restStart = 0;
  bool restStarted = false;
  const auto start = std::chrono::steady_clock::now();
  for (int f = 1; f <= o.frames; ++f) {
    try {
      sim.advanceFrame(wands.next(f, p.frameTime));
    } catch (const SimulationUnstable& e) {
      std::printf("FAIL frame %d: %s\n", f, e.what());
      return 1;
    }
    if (sim.lastEvents().pinchedOff) ++pinches;
    if (f % 400 == 120 && sim.pinch()) ++pinches;
    if (f % 400 == 300 && !sim.burst().active() && sim.film().state.size() > 0) {
      sim.startBurst(sim.topParticle());
      ++pokes;
    }
    if (sim.lastEvents().finished || f % 400 == 399) {
      sim.dip(wands.current());
      ++dips;
      restStarted = false;
    }
    if (!allFinite(sim.film().state)) {
      std::printf("FAIL frame %d: a non-finite particle\n", f);
      return 1;
    }
    const bool quiet =
        RandomWands::resting(f) && !sim.burst().active() && sim.burst().started < 0 && !sim.lastEvents().pinchedOff;
    if (!quiet) {
      restStarted = false;
    } else if (f % 50 == 10) {
      restStart = mechanicalEnergy(sim);
      restStarted = true;
    } else if (f % 50 == 49 && restStarted) {
      const double growth = (mechanicalEnergy(sim) - restStart) / std::max(std::abs(restStart), 1e-9);
      worstGrowth = std::max(worstGrowth, growth);
      if (growth > 0.02) {
        std::printf("FAIL frame %d: the energy grew by %.2f%% over a rest\n", f, 100 * growth);
        ++failures;
      }
      ++restsChecked;
      restStarted = false;
    }
    if (f % 500 == 0) {  // a long run's figures so far, in case it is stopped
      std::printf(
          "  frame %d: %.1f ms per frame; %d pokes, %d pinch-offs, %d dips, %d rests checked, largest energy "
          "change over a rest %+.2f%%\n",
          f, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / f, pokes,
          pinches, dips, restsChecked, 100 * worstGrowth);
      std::fflush(stdout);
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "%d frames in %.0f s (%.1f ms per frame): %d pokes, %d pinch-offs, %d dips, %d rests checked, largest "
      "energy change over a rest %+.2f%%, %d failures\n",
      o.frames, seconds, 1e3 * seconds / o.frames, pokes, pinches, dips, restsChecked, 100 * worstGrowth, failures);
  return failures ? 1 : 0;
}
