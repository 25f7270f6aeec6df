// Stress command for the implicit step: random wand motion at h = 0.02 s for many frames on a large
// film, with pokes, pinch-offs and re-dips, as tests/implicit_step_test.cpp's RandomAbuse does at 1,000
// particles. It checks each frame for an instability stop or a non-finite particle, and over every quiet rest
// of the wands (no burst, no event, the wire's loop not swinging; frames 10-49 of a rest, after the pushed air
// has passed) that the film's mechanical energy (kinetic, gravity, and the springs' energy or 2 gamma x area)
// does not grow by more than 2% of itself (drainage shifts the elasticity by less than that over a second). Prints the
// counts, the largest growth seen and the wall time per frame; exits 1 on any failure.
//
// Run (minutes: under nice):
//   nice -n 19 ./build/bench/gb_stress_bench --particles 25650 --frames 10000 [--tension-model 1] [--seed N]
//   nice -n 19 ./build/bench/gb_stress_bench --particles 100000 --frames 1000
// Finding a failure's cause without stepping the thousands of frames before it again:
//   --checkpoint-at F [--checkpoint-file PATH]  writes the film, the wands and their generator after frame F
//   --resume PATH                                goes on from there (a new Simulation of that film: its contact list
//                                                and pressure are found again, so the run is close to, not equal to,
//                                                the uninterrupted one)
//   --trace-from F --trace-to F                  prints each frame's energy terms and what changed them (EnergyLedger)
//   --param NAME=VALUE                           changes a parameter (e.g. solverSweeps=30, collisionStiffness=0,
//                                                energyBudget=0, energyNeutralContraction=1: docs/model.md
//                                                "Energy budget" says what each does)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench/film_checkpoint.h"
#include "capture/scripted_gestures.h"
#include "simulation/simulation.h"
#include "stages/stages.h"

namespace {

using namespace gb;

struct Options {
  int particles = 25650;
  int frames = 10000;
  int tensionModel = 0;
  unsigned seed = 42;
  int traceFrom = 0, traceTo = -1;  // frames whose energy terms are printed one by one
  int checkpointAt = 0;             // write the film after this frame to checkpointFile (0: never)
  std::string checkpointFile = "stress_checkpoint.bin";
  std::string resume;                                  // start from this checkpoint instead of a new dip
  std::vector<std::pair<std::string, double>> params;  // --param NAME=VALUE, applied after the options above
};

Options parse(int argc, char** argv) {
  Options o;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string flag = argv[k];
    if (flag == "--param") {
      const std::string assignment = argv[k + 1];
      const size_t eq = assignment.find('=');
      if (eq == std::string::npos) {
        std::fprintf(stderr, "--param wants NAME=VALUE, got %s\n", assignment.c_str());
        std::exit(2);
      }
      o.params.emplace_back(assignment.substr(0, eq), std::strtod(assignment.c_str() + eq + 1, nullptr));
      continue;
    }
    if (flag == "--checkpoint-file" || flag == "--resume") {
      (flag == "--resume" ? o.resume : o.checkpointFile) = argv[k + 1];
      continue;
    }
    const long value = std::strtol(argv[k + 1], nullptr, 10);
    if (flag == "--particles")
      o.particles = static_cast<int>(value);
    else if (flag == "--frames")
      o.frames = static_cast<int>(value);
    else if (flag == "--tension-model")
      o.tensionModel = static_cast<int>(value);
    else if (flag == "--seed")
      o.seed = static_cast<unsigned>(value);
    else if (flag == "--trace-from")
      o.traceFrom = static_cast<int>(value);
    else if (flag == "--trace-to")
      o.traceTo = static_cast<int>(value);
    else if (flag == "--checkpoint-at")
      o.checkpointAt = static_cast<int>(value);
    else {
      std::fprintf(stderr,
                   "unknown option %s (--particles N --frames N --tension-model 0|1 --seed N --trace-from F "
                   "--trace-to F --checkpoint-at F --checkpoint-file PATH --resume PATH --param NAME=VALUE)\n",
                   flag.c_str());
      std::exit(2);
    }
  }
  if (o.particles < 100 || o.frames < 1 || (o.tensionModel != 0 && o.tensionModel != 1)) {
    std::fprintf(stderr, "need --particles >= 100, --frames >= 1, --tension-model 0 or 1\n");
    std::exit(2);
  }
  return o;
}

// The tension's energy at the film's positions with the given elasticities (N/m per particle) and rest lengths: the
// springs of Eq. (3), or in the physical model each triangle's mean 2 gamma times its area less the Gibbs rise of
// gamma that 2 gamma a counts as stored (2 gamma a - filmTensionEnergy, at the film's areas and liquid) (J).
double tensionEnergy(const Params& p, const Film& film, const std::vector<float>& elasticity,
                     const std::vector<float>& rest) {
  const Topology& topo = film.topology;
  const State& s = film.state;
  double sum = 0;
  if (p.tensionModel == 1) {
    for (size_t i = 0; i < s.size(); ++i)
      if (s.alive[i] && s.voronoiArea[i] > 0) {
        const float surfactant = surfactantLiquid(p, s.mass[i]);
        sum -= filmTension(p, surfactant / s.voronoiArea[i]) * double{s.voronoiArea[i]} -
               filmTensionEnergy(p, surfactant, s.voronoiArea[i]);
      }
    for (size_t t = 0; t < topo.triangleCount(); ++t) {
      const uint32_t* c = &topo.triangles[3 * t];
      const Vec3 twiceAreaNormal =
          (s.position.get(c[1]) - s.position.get(c[0])).cross(s.position.get(c[2]) - s.position.get(c[0]));
      sum +=
          (elasticity[c[0]] + elasticity[c[1]] + elasticity[c[2]]) / 3.0 * 0.5 * twiceAreaNormal.cast<double>().norm();
    }
    return sum;
  }
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    const double stretch = (s.position.get(a) - s.position.get(b)).cast<double>().norm() - rest[k];
    sum += springEnergyOf<double>(0.5f * (elasticity[a] + elasticity[b]), stretch);
  }
  return sum;
}

// Kinetic + gravity + the tension's potential (springs of Eq. 3, or filmTensionEnergy in the physical model), J.
double mechanicalEnergy(Simulation& sim) {
  const FrameStats st = sim.stats();  // refreshes the elasticities at the film's positions
  return st.kineticEnergy + st.potentialEnergy + st.elasticEnergy;
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
  // The generator and the tips' velocities as text, and back (checkpoints); the tips' positions are the film's
  // wands.
  [[nodiscard]] std::string save() const {
    std::ostringstream out;
    out << rng_;
    for (const Vec3& v : velocity_) out << ' ' << v.x() << ' ' << v.y() << ' ' << v.z();
    return out.str();
  }
  void restore(const std::string& saved, const WandState& wands) {
    std::istringstream in(saved);
    in >> rng_;
    for (Vec3& v : velocity_) in >> v.x() >> v.y() >> v.z();
    if (!in) throw std::runtime_error("the checkpoint's wand generator state is unreadable");
    wands_ = wands;
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

// Diagnostics (--trace-from/--trace-to): each frame's change of the film's energy split by its cause. The step's own
// change is taken with the stiffness (elasticity) and rest lengths the step used, those of the frame before; what
// the rest-length rules between frames (yield, contraction, payout) and the new elasticities then add at the new
// positions is printed apart, with the contact penalty's energy and the free bubble's air (Boyle) energy.
class EnergyLedger {
 public:
  void trace(int frame, Simulation& sim) {
    const FrameStats st = sim.stats();  // refreshes the elasticities at the new positions
    const Film& film = sim.film();
    auto tension = [&](const std::vector<float>& elasticity, const std::vector<float>& rest) {
      return tensionEnergy(sim.params(), film, elasticity, rest);
    };
    const double tensionNow = tension(film.state.elasticity, film.topology.restLength);
    const Topology& topo = film.topology;
    const double moving = st.kineticEnergy + st.potentialEnergy;
    const bool sameSprings = topo.springCount() == rest_.size() && film.state.size() == elasticity_.size() &&
                             contacts_.size() > film.state.size();
    std::printf(
        "  trace %d: n %zu closed %d burst %d K %.5f G %.5f tension %.5f contacts %.6f (%zu pairs) air %.6f V %.5f",
        frame, st.particles, int(topo.isClosed()), int(sim.burst().active()), st.kineticEnergy, st.potentialEnergy,
        tensionNow, contactEnergy(sim.params(), film, topo.contacts), contactPairs(film), gasEnergy(sim), st.volume);
    const double held = contactEnergy(sim.params(), film, topo.contacts) + gasEnergy(sim);
    if (sameSprings) {  // the step with the contact list it used (found after the frame before), then the new list's
      const double stepped =
          moving + contactEnergy(sim.params(), film, contacts_) + gasEnergy(sim) + tension(elasticity_, rest_);
      const double listed = moving + held + tension(elasticity_, rest_);
      const double rested = moving + held + tension(elasticity_, topo.restLength);
      std::printf(" | step %+.5f new contact list %+.5f rest-lengths %+.5f elasticity %+.5f", stepped - last_,
                  listed - stepped, rested - listed, moving + held + tensionNow - rested);
    }
    if (sameSprings) printAdmittedPairs(sim.params(), film);
    if (topo.isClosed()) printBoyleMismatch(sim);
    std::printf("\n");
    std::fflush(stdout);
    elasticity_ = film.state.elasticity;
    rest_ = topo.restLength;
    contacts_ = topo.contacts;
    last_ = moving + held + tensionNow;
  }

 private:
  // The contact penalty k_c/2 (d_c - |x_i - x_j|)^2 of the pairs in a contact list (Topology::contacts), d_c the
  // pair's rest distance.
  static double contactEnergy(const Params& p, const Film& film, const std::vector<uint32_t>& c) {
    const State& s = film.state;
    if (c.size() < s.size() + 1) return 0;
    const size_t base = s.size() + 1;
    double sum = 0;
    for (size_t i = 0; i < s.size(); ++i)
      for (uint32_t k = c[i]; k < c[i + 1]; ++k) {
        const uint32_t j = c[base + k];
        const double len = (s.position.get(i) - s.position.get(j)).cast<double>().norm();
        const double rest = contactRestDistance(c, s.size(), k);
        if (j > i && len < rest) sum += 0.5 * p.collisionStiffness * std::pow(rest - len, 2);
      }
    return sum;
  }
  // The pairs the new contact list holds and the last one did not, already closer than the collision distance, the
  // penalty energy they bring (none since they enter at their separation: contactRestDistanceAfter), and how many of
  // those are within two springs of each other along the film (the same sheet, not a fold).
  void printAdmittedPairs(const Params& p, const Film& film) const {
    const Topology& topo = film.topology;
    const State& s = film.state;
    const size_t base = s.size() + 1;
    size_t admitted = 0, nearOnSheet = 0;
    double energy = 0;
    for (uint32_t i = 0; i < s.size(); ++i) {
      const auto oldFirst = contacts_.begin() + base + contacts_[i],
                 oldLast = contacts_.begin() + base + contacts_[i + 1];
      for (uint32_t k = topo.contacts[i]; k < topo.contacts[i + 1]; ++k) {
        const uint32_t j = topo.contacts[base + k];
        if (j < i || std::binary_search(oldFirst, oldLast, j)) continue;
        const float len = (s.position.get(i) - s.position.get(j)).norm();
        if (!(len < p.collisionDistance)) continue;
        ++admitted;
        const float rest = contactRestDistance(topo.contacts, s.size(), k);
        energy += 0.5 * p.collisionStiffness * std::pow(std::max(0.0f, rest - len), 2);
        bool near = false;
        for (uint32_t a = topo.springOffset[i]; a < topo.springOffset[i + 1] && !near; ++a) {
          const uint32_t m = topo.springNeighbour[a];
          for (uint32_t b = topo.springOffset[m]; b < topo.springOffset[m + 1] && !near; ++b)
            near = topo.springNeighbour[b] == j;
        }
        nearOnSheet += near;
      }
    }
    std::printf(" | admitted overlapping %zu pairs (%.5f J), %zu of them two springs apart", admitted, energy,
                nearOnSheet);
  }
  // Boyle's excess pressure on a closed film (boyleForce: the excess times the volume's gradient, whose sum over a
  // closed film is zero), against what the Voronoi area along the vertex normal, the smooth film's approximation of it,
  // would give. Prints the net force of each and the power each does at this frame's velocities (W).
  static void printBoyleMismatch(Simulation& sim) {
    const Film& film = sim.film();
    const State& s = film.state;
    const Topology& topo = film.topology;
    const double excess = sim.lastPressure() - sim.params().pressureCoefficient;
    Eigen::Vector3d net = Eigen::Vector3d::Zero(), netVoronoi = Eigen::Vector3d::Zero();
    double power = 0, powerVoronoi = 0;
    for (size_t i = 0; i < s.size(); ++i) {
      if (!s.alive[i]) continue;
      const Eigen::Vector3d used = boyleForce(sim.params(), sim.lastPressure(), topo, s, i).cast<double>();
      const Eigen::Vector3d voronoi = excess * s.voronoiArea[i] * s.normal.get(i).cast<double>();
      const Eigen::Vector3d v = s.velocity.get(i).cast<double>();
      net += used;
      netVoronoi += voronoi;
      power += used.dot(v);
      powerVoronoi += voronoi.dot(v);
    }
    std::printf(" | boyle dP %.3f net %.2e N, Voronoi net %.4f N; power %+.5f W, Voronoi %+.5f W", excess, net.norm(),
                netVoronoi.norm(), power, powerVoronoi);
  }
  static double gasEnergy(Simulation& sim) {
    const Film& film = sim.film();
    return film.topology.isClosed() ? boyleGasEnergy(sim.params(), film.referenceVolume, sim.stats().volume) : 0.0;
  }
  static size_t contactPairs(const Film& film) {
    const size_t listed = film.topology.contacts.size(), heads = film.state.size() + 1;
    return listed > heads ? (listed - heads) / 2 : 0;
  }
  std::vector<float> elasticity_, rest_;
  std::vector<uint32_t> contacts_;
  double last_ = 0;
};

bool allFinite(const State& s) {
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i] && !(s.position.get(i).allFinite() && s.velocity.get(i).allFinite())) return false;
  return true;
}

// The largest relative energy change over the rests checked, as a percentage, or "none" before the first rest.
std::string largestChange(int restsChecked, double worstGrowth) {
  if (restsChecked == 0) return "none";
  char text[32];
  std::snprintf(text, sizeof text, "%+.2f%%", 100 * worstGrowth);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  Params p;
  p.particlesAtFullSolution = o.particles;
  p.tensionModel = o.tensionModel;
  try {
    for (const auto& [name, value] : o.params) setParameter(p, name, value);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  RandomWands wands(o.seed, gestureAt(Gesture::Straight, GestureOptions{}, 0.0));
  std::unique_ptr<Simulation> simulation;
  int firstFrame = 1;
  if (o.resume.empty()) {
    simulation = std::make_unique<Simulation>(p, WandTool{}, wands.current());
  } else {  // a new Simulation of the saved film: its burst, aerosol and wand arming start afresh
    FilmCheckpoint c = readCheckpoint(o.resume);
    wands.restore(c.randomWands, c.wands);
    firstFrame = c.frame + 1;
    simulation = std::make_unique<Simulation>(p, std::move(c.film), c.wands);
    simulation->setWandsArmed(c.wandsArmed);
  }
  Simulation& sim = *simulation;
  std::printf("stress: %zu particles, %s tension, frames %d to %d of random wand motion (seed %u)\n",
              sim.film().state.size(), o.tensionModel ? "physical" : "springs", firstFrame, o.frames, o.seed);
  std::fflush(stdout);
  int pokes = 0, pinches = 0, dips = 0, restsChecked = 0, failures = 0;
  double worstGrowth = -1e30, restStart = 0;
  bool restStarted = false;
  Vec3 loopHangBefore = sim.film().loopHang;
  EnergyLedger ledger;
  const auto start = std::chrono::steady_clock::now();
  for (int f = firstFrame; f <= o.frames; ++f) {
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
    if (f >= o.traceFrom && f <= o.traceTo) ledger.trace(f, sim);
    if (f == o.checkpointAt)
      writeCheckpoint(o.checkpointFile, {sim.film(), wands.current(), sim.wandsArmed(), f, wands.save()});
    if (!allFinite(sim.film().state)) {
      std::printf("FAIL frame %d: a non-finite particle\n", f);
      return 1;
    }
    // A rest is quiet once the wire is still too: after the tips stop, the loop may still be swinging towards
    // gravity (swingLoop), and a moving wire does work on the film.
    const bool wireStill = sim.film().loopHang == loopHangBefore;
    loopHangBefore = sim.film().loopHang;
    const bool quiet = RandomWands::resting(f) && wireStill && !sim.burst().active() && sim.burst().started < 0 &&
                       !sim.lastEvents().pinchedOff;
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
          "change over a rest %s\n",
          f,
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
              (f - firstFrame + 1),
          pokes, pinches, dips, restsChecked, largestChange(restsChecked, worstGrowth).c_str());
      std::fflush(stdout);
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int stepped = o.frames - firstFrame + 1;
  std::printf(
      "frames %d to %d in %.0f s (%.1f ms per frame): %d pokes, %d pinch-offs, %d dips, %d rests checked, largest "
      "energy change over a rest %s, %d failures\n",
      firstFrame, o.frames, seconds, 1e3 * seconds / std::max(stepped, 1), pokes, pinches, dips, restsChecked,
      largestChange(restsChecked, worstGrowth).c_str(), failures);
  return failures ? 1 : 0;
}
