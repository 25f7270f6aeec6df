// Bursting (Section 6.1, Algorithm 3), the hole's speed, the aerosol, and the mesh after every event.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <queue>
#include <set>

#include "capture/scripted_gestures.h"
#include "simulation/simulation.h"
#include "tests/mesh_checks.h"

namespace gb {
namespace {

WandState restingWands() { return gestureAt(Gesture::Straight, GestureOptions{}, 0.0); }

size_t living(const State& s) { return static_cast<size_t>(std::count(s.alive.begin(), s.alive.end(), 1u)); }

// Runs frames with the wands still until the burst has finished (or maxFrames), checking the mesh after
// every topology event.
int runUntilBurst(Simulation& sim, const WandState& wands, int maxFrames = 500) {
  for (int f = 1; f <= maxFrames; ++f) {
    sim.advanceFrame(wands);
    if (sim.lastEvents().particlesRemoved > 0) {
      test::eulerCharacteristic(sim.film().topology);  // asserts orientation and manifoldness
      test::expectAdjacencyMatchesTriangles(sim.film().topology);
      for (uint32_t v : sim.film().topology.triangles) EXPECT_TRUE(sim.film().state.alive[v]);
    }
    if (sim.lastEvents().finished) return f;
  }
  return -1;
}

TEST(Bursting, OneCrackRemovesTheWholeFilmOnceIntoDropletsCarryingItsLiquid) {
  Params p;
  p.particlesAtFullSolution = 1500;
  p.gravityY = 0.0f;  // droplets stay in the air: all of them are counted
  p.aerosolLifetime = 100.0f;
  p.evaporationRate = 0.0f;  // saturated air: the film's liquid goes into the droplets and nowhere else
  Simulation sim(p, WandTool{}, restingWands());
  const size_t triangles = sim.film().topology.triangleCount();
  const State& s = sim.film().state;
  const double liquidMass = p.liquidDensity * std::accumulate(s.liquid.begin(), s.liquid.end(), 0.0);
  const float thinnest = *std::min_element(s.thickness.begin(), s.thickness.end());
  sim.startBurst(sim.topParticle());
  int started = 0, finished = 0;
  size_t droplets = 0;
  for (int f = 0; f < 300; ++f) {
    sim.advanceFrame(restingWands());
    started += sim.lastEvents().started;
    finished += sim.lastEvents().finished;
    droplets += sim.lastEvents().dropletsEmitted;
  }
  EXPECT_EQ(living(sim.film().state), 0u);
  EXPECT_EQ(sim.film().topology.triangleCount(), 0u);
  EXPECT_EQ(started, 1);
  EXPECT_EQ(finished, 1);
  // A few hundred to a few thousand droplets, gathered a few centimetres at a time: far fewer
  // than the film's triangles.
  EXPECT_EQ(sim.aerosol().size(), droplets);
  EXPECT_GE(droplets, 200u);
  EXPECT_LE(droplets, 5000u);
  EXPECT_LT(droplets, triangles / 2);
  // Every particle's liquid is split over its triangles: the aerosol carries the film's liquid. 1% is required;
  // the bookkeeping is exact but for float rounding in the sums, so 1e-5 is asked.
  const double aerosolMass = std::accumulate(sim.aerosol().mass.begin(), sim.aerosol().mass.end(), 0.0);
  EXPECT_NEAR(aerosolMass, liquidMass, 1e-5 * liquidMass);
  // None flies faster than the rim can carry liquid: the Taylor-Culick speed of the thinnest film (drag, with
  // gravity off, only slows them).
  const float rim = taylorCulickSpeed(p, thinnest);
  for (size_t i = 0; i < sim.aerosol().size(); ++i)
    EXPECT_LE(sim.aerosol().velocity.get(i).norm(), rim * (1.0f + 1e-5f)) << "droplet " << i;
}

TEST(Bursting, MeshStaysManifoldAndTheOneRingMatchesAfterEveryEvent) {
  Params p;
  p.particlesAtFullSolution = 1200;
  Simulation sim(p, WandTool{}, restingWands());
  sim.startBurst(sim.film().state.size() - 1);  // an interior particle
  EXPECT_GT(runUntilBurst(sim, restingWands()), 0);
}

TEST(Bursting, AParticleThinnerThanTheThresholdCracksByItself) {
  Params p;
  p.particlesAtFullSolution = 800;
  Simulation sim(p, WandTool{}, restingWands());
  const size_t victim = sim.film().state.size() - 1;
  sim.film().state.liquid[victim] *= 1e-4f;  // drained to 0.35 nm, under lambda_thi = 35 nm
  sim.advanceFrame(restingWands());
  EXPECT_TRUE(sim.lastEvents().started);
  EXPECT_FALSE(sim.film().state.alive[victim]);
}

TEST(Bursting, PapersModeOpensOneRingPerFrame) {
  Params p;
  p.particlesAtFullSolution = 800;
  p.holeOpening = 1;
  Simulation sim(p, WandTool{}, restingWands());
  const size_t origin = sim.film().state.size() - 1;
  // Rings of the one-ring graph around the origin, by breadth-first search on the intact film.
  const Topology topo = sim.film().topology;
  std::vector<int> ring(topo.particleCount(), -1);
  std::queue<uint32_t> todo;
  ring[origin] = 0;
  todo.push(static_cast<uint32_t>(origin));
  while (!todo.empty()) {
    const uint32_t i = todo.front();
    todo.pop();
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k)
      if (ring[topo.springNeighbour[k]] < 0) {
        ring[topo.springNeighbour[k]] = ring[i] + 1;
        todo.push(topo.springNeighbour[k]);
      }
  }
  sim.startBurst(origin);
  for (int frame = 1; frame <= 4; ++frame) {
    sim.advanceFrame(restingWands());
    for (size_t i = 0; i < ring.size(); ++i)
      EXPECT_EQ(sim.film().state.alive[i] == 0, ring[i] < frame) << "frame " << frame << " particle " << i;
  }
}

// A flat, uniform film (no gravity, no drainage) cracked at its centre; returns (V_fit, burst duration).
std::pair<double, double> taylorCulickBurst(int particles, float frameTime, float thickness) {
  Params p;
  p.particlesAtFullSolution = particles;
  p.frameTime = frameTime;
  p.gravityY = 0.0f;
  p.drainageRate = 0.0f;
  p.areaWeight = thickness / 100e-6f;
  WandTool ring;
  ring.kind = ToolKind::Ring;
  ring.ringRadius = 0.5f;
  Simulation sim(p, ring, restingWands());
  const Vec3 centre = restingWands().rightPosition;
  size_t origin = 0;
  for (size_t i = 0; i < sim.film().state.size(); ++i)
    if ((sim.film().state.position.get(i) - centre).norm() < (sim.film().state.position.get(origin) - centre).norm())
      origin = i;
  const Vec3 start = sim.film().state.position.get(origin);
  sim.startBurst(origin);
  EXPECT_GT(runUntilBurst(sim, restingWands()), 0);
  // Least-squares slope of distance from the origin against arrival time, through the origin.
  const BurstFront& front = sim.burst();
  double rt = 0, tt = 0;
  for (size_t i = 0; i < front.arrival.size(); ++i) {
    const double t = front.arrival[i] - front.started, r = (sim.film().state.position.get(i) - start).norm();
    rt += r * t;
    tt += t * t;
  }
  return {rt / tt, front.finished - front.started};
}

TEST(Bursting, TaylorCulickHoleGrowsLinearlyAtTheRightSpeedWhateverStepAndResolution) {
  const float e = 1e-6f;  // a 1 um film
  Params p;
  const double expected = std::sqrt(2.0 * p.surfaceTension / (p.liquidDensity * e));  // 7.07 m/s
  const auto [speedCoarse, durationCoarse] = taylorCulickBurst(1500, 0.02f, e);
  const auto [speedFine, durationFine] = taylorCulickBurst(4000, 0.02f, e);
  const auto [speedShortStep, durationShortStep] = taylorCulickBurst(1500, 0.005f, e);
  std::printf("V_TC %.3f m/s; fitted %.3f (1500), %.3f (4000), %.3f (1500, h/4); bursts %.4f %.4f %.4f s\n", expected,
              speedCoarse, speedFine, speedShortStep, durationCoarse, durationFine, durationShortStep);
  // The front follows mesh edges, whose paths are up to 2/sqrt(3) longer than straight lines on a
  // triangulated lattice: the 15% bound covers that.
  EXPECT_NEAR(speedCoarse, expected, 0.15 * expected);
  EXPECT_NEAR(speedFine, expected, 0.15 * expected);
  EXPECT_NEAR(durationFine, durationCoarse, 0.15 * durationCoarse);
  EXPECT_NEAR(durationShortStep, durationCoarse, 0.15 * durationCoarse);
}

TEST(Bursting, ANewDipAfterABurstGivesAFreshFilm) {
  Params p;
  p.particlesAtFullSolution = 600;
  Simulation sim(p, WandTool{}, restingWands());
  for (int cycle = 0; cycle < 3; ++cycle) {
    sim.startBurst(sim.topParticle());
    ASSERT_GT(runUntilBurst(sim, restingWands()), 0) << "cycle " << cycle;
    EXPECT_EQ(living(sim.film().state), 0u);
    sim.dip(restingWands());
    EXPECT_EQ(living(sim.film().state), 600u);
    EXPECT_FALSE(sim.burst().active());
  }
}

}  // namespace
}  // namespace gb
