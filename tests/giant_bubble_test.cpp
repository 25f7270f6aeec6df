// The default performance (scenes/default.toml), simulated as the README's main job runs it: a giant bubble is
// drawn, let go, flies free and bursts; the paper's Figures 10e against 10a and 14d as built-in scenes; the film's
// liquid accounted for through growth, pinch-off and burst. Each bound is what the model is required to do unless
// its comment says why it is tighter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include "capture/scripted_gestures.h"
#include "scene/scene_file.h"
#include "simulation/simulation.h"
#include "stages/stages.h"
#include "topology/film_growth.h"

namespace gb {
namespace {

struct PerformanceRecord {
  double firstArea = 0, peakArea = 0, peakVolume = 0;
  double pinchTime = -1, burstTime = -1;
  std::string burstCause;
  double peakWandSpeed = 0, peakFilmSpeedOutsideBursts = 0;
  double volumeAtPinch = 0, volumeOneSecondLater = 0;
  double roundnessOneSecondLater = 0;  // area over the area of a sphere of the same volume (1: a sphere)
  double foldedOneSecondLater = 0;     // the fraction of triangles folded (foldedTriangles)
};

// The fraction of the film's triangles whose corners' normals differ by more than 37 degrees (cosine 0.8): a
// film crumpled into fine folds, which the renderer shows as a glittering patch, not a smooth bubble.
double foldedTriangles(const Film& film) {
  const Topology& topo = film.topology;
  const State& s = film.state;
  size_t folded = 0;
  for (size_t t = 0; t < topo.triangleCount(); ++t) {
    const uint32_t* tri = &topo.triangles[3 * t];
    float least = 1.0f;
    for (int c = 0; c < 3; ++c) least = std::min(least, s.normal.get(tri[c]).dot(s.normal.get(tri[(c + 1) % 3])));
    folded += least < 0.8f;
  }
  return topo.triangleCount() ? static_cast<double>(folded) / static_cast<double>(topo.triangleCount()) : 0.0;
}

// The default performance, with `sweeps` solver sweeps (0: the scene's), for `seconds` (0: the scene's duration),
// with Params::gibbsFloorThickness (negative: the scene's). `liveSeed` > 0 steps it as `live` does on a machine
// that cannot keep up (app/show/realtime_pacer.h): each step takes 3 to 6 sweeps and covers one or two frames, drawn
// from a generator seeded with it.
PerformanceRecord performDefaultScene(int sweeps = 0, double seconds = 0, float gibbsFloorThickness = -1,
                                      unsigned liveSeed = 0) {
  const Scene scene = resolveScene("default");
  RunOptions run = scene.run;
  EXPECT_EQ(run.input.spec(), "script:giant");
  if (sweeps > 0) run.params.solverSweeps = sweeps;
  if (gibbsFloorThickness >= 0) run.params.gibbsFloorThickness = gibbsFloorThickness;
  const GestureOptions& g = run.gestureOptions;
  Simulation sim(run.params, run.tool, gestureAt(Gesture::Giant, g, 0.0));
  std::mt19937 live(liveSeed);
  PerformanceRecord r;
  r.firstArea = sim.stats().area;
  const long frames = std::lround((seconds > 0 ? seconds : run.duration) / run.params.frameTime);
  for (long f = 1; f <= frames;) {
    if (liveSeed > 0) {
      const int stepFrames = std::uniform_int_distribution<int>(1, 2)(live);
      sim.setSolverSweeps(std::uniform_int_distribution<int>(3, 6)(live));
      sim.setFrameTime(run.params.frameTime * static_cast<float>(stepFrames));
      f += stepFrames - 1;
    }
    const WandState wands = gestureAt(Gesture::Giant, g, static_cast<double>(f) * run.params.frameTime);
    ++f;
    r.peakWandSpeed = std::max({r.peakWandSpeed, static_cast<double>(wands.leftVelocity.norm()),
                                static_cast<double>(wands.rightVelocity.norm())});
    sim.advanceFrame(wands);
    const FrameStats st = sim.stats();
    const TopologyEvents& e = sim.lastEvents();
    if (e.pinchedOff) {
      r.pinchTime = st.time;
      r.volumeAtPinch = st.volume;
    }
    if (r.pinchTime >= 0 && r.volumeOneSecondLater == 0 && st.time >= r.pinchTime + 1.0 && r.burstTime < 0) {
      r.volumeOneSecondLater = st.volume;
      r.roundnessOneSecondLater = st.area / std::cbrt(36.0 * std::numbers::pi * st.volume * st.volume);
      r.foldedOneSecondLater = foldedTriangles(sim.film());  // stats() refreshed the normals
    }
    if (e.started && r.burstTime < 0) {
      r.burstTime = st.time;
      r.burstCause = e.cause != nullptr ? e.cause : "";
    }
    if (r.burstTime < 0) {
      r.peakArea = std::max(r.peakArea, st.area);
      r.peakVolume = std::max(r.peakVolume, st.volume);
      r.peakFilmSpeedOutsideBursts = std::max(r.peakFilmSpeedOutsideBursts, st.maxSpeed);
    }
  }
  return r;
}

TEST(GiantBubble, DefaultPerformanceBlowsReleasesAndBurstsABubble) {
  const PerformanceRecord r = performDefaultScene();
  std::printf(
      "area %.2f -> %.2f m^2, volume %.2f m^3, pinch-off at %.2f s, burst (%s) at %.2f s, fastest film particle %.1f "
      "m/s against the wands' %.1f m/s, roundness a second after pinch-off %.2f, folded triangles %.1f%%\n",
      r.firstArea, r.peakArea, r.peakVolume, r.pinchTime, r.burstCause.c_str(), r.burstTime,
      r.peakFilmSpeedOutsideBursts, r.peakWandSpeed, r.roundnessOneSecondLater, 100.0 * r.foldedOneSecondLater);
  // Measured: area 0.63 -> 3.48 m^2, volume 0.60 m^3, pinch-off at 1.86 s, burst by the floor at 5.08 s, fastest
  // film particle 2.8 m/s against the wands' 2.2 m/s, roundness a second after pinch-off 1.09, 2.1% folded.
  EXPECT_GE(r.peakArea, 3.0 * r.firstArea) << "the bag is not giant: peak area " << r.peakArea << " m^2";
  EXPECT_GE(r.peakVolume, 0.5) << "peak volume " << r.peakVolume << " m^3";
  ASSERT_GE(r.pinchTime, 0.0) << "the wands closed but the film never pinched off";
  ASSERT_GE(r.burstTime, 0.0) << "the free bubble never burst";
  EXPECT_GE(r.burstTime - r.pinchTime, 1.0) << "the free bubble lived " << r.burstTime - r.pinchTime << " s";
  EXPECT_FALSE(r.burstCause.empty());
  // No runaway: the film never outruns the air the wands push by more than a factor of 4.
  EXPECT_LE(r.peakFilmSpeedOutsideBursts, 4.0 * r.peakWandSpeed)
      << "fastest film particle " << r.peakFilmSpeedOutsideBursts << " m/s, wands " << r.peakWandSpeed << " m/s";
  // Boyle's law keeps the free bubble's air: its volume a second after pinch-off within 5% of the volume at
  // closure (the bubble wobbles and the film's springs squeeze it slightly; the Boyle test of a bubble at
  // rest holds 2%).
  EXPECT_NEAR(r.volumeOneSecondLater, r.volumeAtPinch, 0.05 * r.volumeAtPinch);
  // A soap film has no slack: the long bag pulls round around its air (contractSlackSprings). A second after
  // pinch-off its area is within 25% of a sphere's of the same volume (measured 1.09; 1.37 when the slack film
  // hangs in wrinkles; it still wobbles, and its closing seam is a fold).
  EXPECT_LT(r.roundnessOneSecondLater, 1.25) << "the free bubble hangs in folds";
  // Nor is it crumpled: a second after pinch-off at most 3% of its triangles are folded (corner normals over 37
  // degrees apart). Measured 2.1%, and 1.3-2.5% with the stroke 1-2% slower or faster: the band the stroke draws off
  // the wire is fed to a new film's thickness (film_growth.h), and film as thick as the dip is not contracted, so the
  // seam keeps a few more folds than the 0.6-1.3% of a bag whose band thinned (which burst real performers' films).
  // 6.1% without the merging of crowded thick particles (mergeCrowdedParticles), whose folds glitter on the seam.
  EXPECT_LT(r.foldedOneSecondLater, 0.03) << "the free bubble is crumpled";
}

TEST(GiantBubble, AGibbsFloorLetsTheFreeBubbleLiveWhateverTheSolversSweeps) {
  // `live` takes fewer sweeps when it falls behind, and a better converged step would take more. With Eq. (4)'s
  // Gibbs elasticity falling all the way down (the default), the thinnest film is the softest: the free bubble
  // bursts by thinning at 3.04 s with 4 sweeps and at 1.92 s with 10, and lives to the floor (5.54 s) only at the
  // default 6. Held below gibbsFloorThickness = 1.5 um (the default scene's),
  // neither bursts by thinning within 3.5 s, 1.64 s after pinch-off (measured: 4 sweeps no burst within 7 s, 10
  // sweeps by the floor at 6.04 s). The bound is the failure itself: any burst by thinning.
  for (int sweeps : {4, 10}) {
    const PerformanceRecord r = performDefaultScene(sweeps, 3.5, 1.5e-6f);
    ASSERT_GE(r.pinchTime, 0.0) << sweeps << " sweeps: the film never pinched off";
    EXPECT_NE(r.burstCause, "thin") << sweeps << " sweeps: the free bubble burst by thinning at " << r.burstTime
                                    << " s";
  }
  // And without the floor the same film does burst by thinning at 10 sweeps: the test sees the mechanism.
  EXPECT_EQ(performDefaultScene(10, 3.5, 0.0f).burstCause, "thin");
}

TEST(GiantBubble, TheFreeBubbleOutlivesItsPinchOffWhateverLiveDoesToTheStep) {
  // `live` changes the sweeps and the step's length from frame to frame with the machine's load. A pinch-off seam
  // that kept the liquid of the film's edge (the last strips, grown as the wire ran dry) over the larger area of the
  // zip's triangles would be 94 nm thick against the film's microns; the seam then stretches as the bag rounds, and
  // the bubble burst by thinning within 0.3 s of pinch-off in one show of six in `live` and in the schedule of
  // seed 5 here (2.12 s). So the seam is wetted to the film's mean thickness (pinch_off.h). Bound: no burst at all
  // by 3.0 s, 1.1 s after pinch-off (the default test asks 1 s of life).
  for (unsigned seed : {3u, 5u, 7u}) {
    const PerformanceRecord r = performDefaultScene(0, 3.0, -1, seed);
    ASSERT_GE(r.pinchTime, 0.0) << "seed " << seed << ": the film never pinched off";
    EXPECT_LT(r.burstTime, 0.0) << "seed " << seed << ": the free bubble burst (" << r.burstCause << ") at "
                                << r.burstTime << " s, " << r.burstTime - r.pinchTime << " s after pinch-off";
  }
}

// A built-in scene driven by its own scripted gesture, at `particles` per full-solution film (fewer than the
// scene's, so the test stays short), until the scene ends or its film has burst away.
struct SceneRecord {
  double peakVolume = 0;
  size_t grownParticles = 0;  // film drawn off the wire
};

SceneRecord performScene(const std::string& name, int particles) {
  const Scene scene = resolveScene(name);
  RunOptions run = scene.run;
  run.params.particlesAtFullSolution = particles;
  const std::string spec = run.input.spec();
  EXPECT_EQ(spec.rfind("script:", 0), 0u) << name << " is driven by " << spec;
  const Gesture gesture = gestureFromName(spec.substr(spec.find(':') + 1));
  Simulation sim(run.params, run.tool, gestureAt(gesture, run.gestureOptions, 0.0));
  SceneRecord r;
  const long frames = std::lround(run.duration / run.params.frameTime);
  for (long f = 1; f <= frames && sim.burst().finished < 0; ++f) {
    sim.advanceFrame(gestureAt(gesture, run.gestureOptions, static_cast<double>(f) * run.params.frameTime));
    r.peakVolume = std::max(r.peakVolume, sim.stats().volume);
    r.grownParticles += sim.lastEvents().particlesAdded;
  }
  return r;
}

// Figure 10e: "when the left and right wands move up and down, the soap bubble is inflated further" than the
// straight stroke of Figure 10a. Both scenes at the same 3,000 particles (fig10e runs 16,000, fig10a 9,500).
TEST(GiantBubble, Fig10eInflatesFurtherThanFig10a) {
  const double straight = performScene("fig10a", 3000).peakVolume, upDown = performScene("fig10e", 3000).peakVolume;
  std::printf("peak volume: fig10a %.3f m^3, fig10e %.3f m^3\n", straight, upDown);
  // Measured when written: 0.20 and 0.46 m^3 (at the scenes' own resolutions 0.18 and 0.52; at fig10a's speed,
  // 0.8 m/s, fig10e still drew 0.34). "Further" is asked to be clear, not a rounding: at least 1.5 times.
  EXPECT_GE(upDown, 1.5 * straight);
}

// Eq. (5) for the ring: its one hand moves the whole frame, so it blows as two wands held together at the hand
// would: twice the one source's V_wm v / (d + D), along -v.
TEST(GiantBubble, TheRingBlowsAsTwoWandsHeldTogetherAtItsHand) {
  Params p;
  p.particlesAtFullSolution = 300;
  WandTool ring;
  ring.kind = ToolKind::Ring;
  WandState w;
  w.rightPosition = Vec3(0.0f, 1.2f, 0.0f);
  w.rightVelocity = Vec3(0.0f, 0.3f, 1.5f);
  w.leftPosition = Vec3(-3.0f, 0.0f, 0.0f);  // the free hand is elsewhere, and still: it plays no part
  const Simulation sim(p, ring, w);
  const StepUniforms u = sim.uniformsFor(w, w, p.frameTime);
  const Vec3 x(0.2f, 1.0f, -0.3f);
  const float d = (x - w.rightPosition).norm();
  const Vec3 expected = -2.0f * u.airVolume * w.rightVelocity / (d + p.airInflowDistance);
  // Float rounding of a few products: 1e-5 relative.
  EXPECT_LT((airInflowAt(p, u, x) - expected).norm(), 1e-5f * expected.norm());
}

// Figure 14d: a single ring raised from bottom to top draws a bubble out of its wet wire. The bound,
// 0.2 m^3 (a sphere of 0.36 m radius, about the ring's own), at 3,000 particles (the scene's 9,500 drew 0.24 m^3,
// 3,000-5,000 drew 0.25-0.27).
TEST(GiantBubble, Fig14dsRingDrawsABubble) {
  const SceneRecord r = performScene("fig14d", 3000);
  std::printf("fig14d: peak volume %.3f m^3, %zu particles drawn off the ring\n", r.peakVolume, r.grownParticles);
  EXPECT_GE(r.peakVolume, 0.2);
  EXPECT_GT(r.grownParticles, 0u) << "the ring's wire drew no new film";
}

double filmLiquid(const Film& film) {
  double sum = 0;
  for (size_t i = 0; i < film.state.size(); ++i)
    if (film.state.alive[i]) sum += film.state.liquid[i];
  return sum;
}

// The default performance at 7,000 particles (the scene's 9,500 free bubble lives seconds; this one bursts soon
// after pinch-off, and is poked if it has not within 0.1 s): the film's liquid, the wet wire's (which growth and
// the pinch-off seam draw on) and the droplets' (emitted so far, whether or not they have landed) always add up
// to what the dip left on film and wire.
TEST(GiantBubble, LiquidIsConservedThroughGrowthPinchOffAndBurst) {
  const Scene scene = resolveScene("default");
  RunOptions run = scene.run;
  run.params.particlesAtFullSolution = 7000;
  run.params.evaporationRate = 0.0f;  // saturated air: the liquid is followed through the events alone
  const GestureOptions& g = run.gestureOptions;
  Simulation sim(run.params, run.tool, gestureAt(Gesture::Giant, g, 0.0));
  const double density = run.params.liquidDensity;
  const double wire0 = sim.film().wireLiquid, total0 = filmLiquid(sim.film()) + wire0;
  double emitted = 0, worstDrift = 0, filmBeforeBurst = 0, pinchTime = -1;
  size_t grownParticles = 0;
  const long frames = std::lround(run.duration / run.params.frameTime);
  for (long f = 1; f <= frames; ++f) {
    const double liquidBefore = filmLiquid(sim.film());
    sim.advanceFrame(gestureAt(Gesture::Giant, g, static_cast<double>(f) * run.params.frameTime));
    const TopologyEvents& e = sim.lastEvents();
    emitted += e.dropletMassEmitted / density;
    grownParticles += e.particlesAdded;
    if (e.pinchedOff) pinchTime = sim.time();
    if (e.started) filmBeforeBurst = liquidBefore;  // nothing grows or pinches in the frame a burst starts
    // Mid-burst, dead particles whose torn triangles still have a living corner hold liquid not yet shed.
    if (!sim.burst().active())
      worstDrift = std::max(worstDrift, std::abs(filmLiquid(sim.film()) + sim.film().wireLiquid + emitted - total0));
    if (sim.burst().finished >= 0) break;
    if (pinchTime >= 0 && sim.burst().started < 0 && sim.time() >= pinchTime + 0.1) sim.startBurst(sim.topParticle());
  }
  ASSERT_GT(grownParticles, 0u) << "the wire drew no new film";
  ASSERT_GE(pinchTime, 0.0) << "the bag burst before it pinched off";
  ASSERT_GE(sim.burst().finished, 0.0) << "the free bubble's burst did not finish";
  EXPECT_LT(sim.film().wireLiquid, wire0) << "growth took liquid from the wire";
  std::printf("wire gave %.3g m^3, droplets %.4g m^3 from a film of %.4g m^3, worst drift %.2g of the total\n",
              wire0 - sim.film().wireLiquid, emitted, filmBeforeBurst, worstDrift / total0);
  // The droplets carry the film's liquid within 1%.
  EXPECT_NEAR(emitted, filmBeforeBurst, 0.01 * filmBeforeBurst);
  // The account is exact up to float rounding (measured ~5e-8); 1e-4 is about one particle's share of the film,
  // so a particle whose liquid is lost or made from nothing fails it.
  EXPECT_LE(worstDrift, 1e-4 * total0);
}

}  // namespace
}  // namespace gb
