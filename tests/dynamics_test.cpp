// The CPU stepper as a whole: behaviour the paper describes and invariants any step must keep.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "capture/scripted_gestures.h"
#include "simulation/simulation.h"

namespace gb {
namespace {

WandState restingWands() { return gestureAt(Gesture::Straight, GestureOptions{}, 0.0); }

double maxAbsZ(const State& s, const Topology& topo) {
  double m = 0;
  for (size_t i = 0; i < s.size(); ++i)
    if (!topo.boundary[i]) m = std::max(m, std::abs(static_cast<double>(s.position.z[i])));
  return m;
}

TEST(Dynamics, FlatFilmOnAFixedRingStaysFlatAndComesToRest) {
  Params p;
  p.particlesAtFullSolution = 800;
  // Saturated air: a film that keeps thinning keeps changing its elasticity (Eq. 4 reads the thickness), and so
  // never quite comes to rest.
  p.evaporationRate = 0.0f;
  WandTool ring;
  ring.kind = ToolKind::Ring;
  const WandState wands = restingWands();
  Simulation sim(p, ring, wands);
  // Push the film 5 mm out of its (vertical) plane in the middle, then let go.
  State& s = sim.film().state;
  const Vec3 centre = wands.rightPosition;
  for (size_t i = 0; i < s.size(); ++i) {
    const float r2 = (s.position.get(i) - centre).squaredNorm() / (ring.ringRadius * ring.ringRadius);
    if (!sim.film().topology.boundary[i]) s.position.z[i] += 0.005f * std::max(0.0f, 1.0f - r2);
  }
  const double startBump = maxAbsZ(s, sim.film().topology);
  double peakKinetic = 0;
  for (int frame = 0; frame < 400; ++frame) {  // 8 s
    sim.advanceFrame(wands);
    peakKinetic = std::max(peakKinetic, sim.stats().kineticEnergy);
  }
  const FrameStats end = sim.stats();
  // Flat: gravity lies in the plane, so the bump must go; 10% of it is left after 8 s of air drag.
  EXPECT_LT(maxAbsZ(sim.film().state, sim.film().topology), 0.1 * startBump);
  // At rest: the kinetic energy fell by more than 1000 from its peak.
  EXPECT_LT(end.kineticEnergy, 1e-3 * peakKinetic);
}

// Mean offset along +z (the wands' direction of motion) of the film's interior from the wand tips, at the
// gesture's peak speed.
double bulgeAtPeakSpeed(float speed) {
  Params p;
  p.particlesAtFullSolution = 1500;
  GestureOptions g;
  g.speed = speed;
  Simulation sim(p, WandTool{}, gestureAt(Gesture::Straight, g, 0.0));
  const int frames = static_cast<int>((g.start + 0.5 * g.duration) / p.frameTime);
  for (int f = 1; f <= frames; ++f)
    sim.advanceFrame(gestureAt(Gesture::Straight, g, static_cast<float>(f) * p.frameTime));
  const float wandZ = gestureAt(Gesture::Straight, g, static_cast<float>(frames) * p.frameTime).leftPosition.z();
  const State& s = sim.film().state;
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < s.size(); ++i)
    if (!sim.film().topology.boundary[i]) {
      sum += s.position.z[i] - wandZ;
      ++n;
    }
  return sum / static_cast<double>(n);
}

TEST(Dynamics, FilmBulgesAgainstTheWandMotionAndMoreWhenFaster) {
  const double slow = bulgeAtPeakSpeed(0.4f), fast = bulgeAtPeakSpeed(0.8f);
  // Section 8 / Figure 14b: the film inflates opposite to the wands' direction of motion (-z here).
  EXPECT_LT(slow, -0.005) << "slow wands: mean film offset " << slow << " m";
  // Twice the speed must bulge at least 20% more (the response is sublinear: the film stiffens as it
  // stretches, and drag grows with speed too).
  EXPECT_LT(fast, 1.2 * slow) << "fast " << fast << " m vs slow " << slow << " m";
}

TEST(Dynamics, InternalForcesSumToZero) {
  Params p;
  p.particlesAtFullSolution = 1500;
  p.gravityY = 0.0f;
  p.airDrag = 0.0f;
  p.airPressureGain = 0.0f;
  p.springDamping = 0.01f;
  Film film = generateFilm(p, WandTool{}, restingWands());
  State& s = film.state;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(-0.01f, 0.01f), speed(-0.5f, 0.5f), stiffness(1.0f, 10.0f);
  for (size_t i = 0; i < s.size(); ++i) {
    s.position.set(i, s.position.get(i) + Vec3(jitter(rng), jitter(rng), jitter(rng)));
    s.velocity.set(i, Vec3(speed(rng), speed(rng), speed(rng)));
  }
  computeGeometry(film.topology, s);
  for (size_t i = 0; i < s.size(); ++i) s.elasticity[i] = stiffness(rng);  // unequal E_i on purpose
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  double magnitude = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    forces(p, StepUniforms{}, p.pressureCoefficient, film.topology, s, i);
    total += s.force.get(i).cast<double>();
    magnitude += s.force.get(i).cast<double>().norm();
  }
  // Each pair force is computed twice from the same floats with opposite signs, so only the float32
  // rounding of the per-particle sums remains: ~1e-7 relative per term.
  EXPECT_LT(total.norm(), 1e-6 * magnitude) << "net internal force " << total.transpose();
}

TEST(Dynamics, TheExplicitReferenceRunsTenThousandStepsWithoutNaNAndWithBoundedEnergy) {
  Params p;  // the default scene: 9500 particles, straight gesture, on the paper's semi-implicit Euler
  p.integrator = 0;
  const GestureOptions g;
  Simulation sim(p, WandTool{}, gestureAt(Gesture::Straight, g, 0.0));
  long steps = 0;
  double worst = 0;
  for (int f = 1; steps < 10000; ++f) {
    ASSERT_NO_THROW(sim.advanceFrame(gestureAt(Gesture::Straight, g, static_cast<float>(f) * p.frameTime)))
        << "frame " << f;
    steps += sim.substepsPerFrame();
    const FrameStats st = sim.stats();
    worst = std::max(worst, st.kineticEnergy + st.elasticEnergy);
    ASSERT_TRUE(std::isfinite(st.kineticEnergy) && std::isfinite(st.elasticEnergy) && std::isfinite(st.volume));
  }
  // The film weighs 0.1 kg/m^2 x 0.63 m^2 = 63 g; 1 J would mean all of it moving at 5.6 m/s, seven
  // times the wands' peak speed.
  EXPECT_LT(worst, 1.0) << "kinetic + elastic energy reached " << worst << " J";
  for (size_t i = 0; i < sim.film().state.size(); ++i) ASSERT_TRUE(sim.film().state.position.get(i).allFinite());
}

TEST(Dynamics, BoylesLawHoldsForAScaledClosedFilm) {
  const Params p;
  const Vec3 centre(0, 1, 0);
  Film sphere = generateSphere(p, centre, 0.5f, 3);
  CpuStepper stepper;
  const float v0 = stepper.volume(sphere, centre);
  for (float scale : {0.8f, 1.1f, 1.5f}) {
    Film scaled = sphere;
    for (size_t i = 0; i < scaled.state.size(); ++i)
      scaled.state.position.set(i, centre + scale * (sphere.state.position.get(i) - centre));
    const float v = stepper.volume(scaled, centre);
    EXPECT_NEAR(v / v0, scale * scale * scale, 1e-5f);
    const float pressure = boylePressure(p, v0, v);
    // P_cur V_cur = P_0 V_0 to float rounding.
    EXPECT_NEAR(pressure * v, p.pressureCoefficient * v0, 1e-5f * p.pressureCoefficient * v0);
  }
}

TEST(Dynamics, CompressedBubblePushesOutExpandedBubblePullsIn) {
  Params p;
  p.gravityY = 0.0f;
  p.elasticityWeight = 1e-4f;  // springs too weak to matter: only the pressure of Eq. (10) acts
  p.springPrestrain = 0.0f;
  const Vec3 centre(0, 1, 0);
  for (float scale : {0.9f, 1.1f}) {
    Simulation sim(p, generateSphere(p, centre, 0.5f, 2), WandState{});  // V_0 taken at the rest shape
    State& s = sim.film().state;
    for (size_t i = 0; i < s.size(); ++i) s.position.set(i, centre + scale * (s.position.get(i) - centre));
    const StepUniforms u = sim.uniformsFor(WandState{}, WandState{}, 1e-4f);
    const float pressure = sim.stepper().run(std::span(&u, 1));
    EXPECT_NEAR(pressure, p.pressureCoefficient / (scale * scale * scale), 2e-3f * p.pressureCoefficient);
    double radial = 0;
    for (size_t i = 0; i < s.size(); ++i) radial += s.velocity.get(i).dot((s.position.get(i) - centre).normalized());
    if (scale < 1) {
      EXPECT_GT(radial, 0.0) << "a compressed bubble must expand";
    } else {
      EXPECT_LT(radial, 0.0) << "an expanded bubble must shrink";
    }
  }
}

TEST(Dynamics, ANonFiniteStateStopsWithAClearError) {
  Params p;
  p.particlesAtFullSolution = 300;
  Simulation sim(p, WandTool{}, restingWands());
  const size_t interior = sim.film().state.size() - 1;  // interior particles come after the boundary
  sim.film().state.position.x[interior] = std::numeric_limits<float>::quiet_NaN();
  try {
    sim.advanceFrame(restingWands());
    FAIL() << "no error for a NaN position";
  } catch (const SimulationUnstable& e) {
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("t = 0.02"), std::string::npos) << e.what();
  }
}

// The explicit step's bound includes the air coupling (docs/model.md "Air coupling", "The explicit reference and its
// stability bound"): at 1,000 Pa s/m^3 (100x the default) the coupling's damping rate kappa Area_wm / filmInertia is
// ~4,000/s, seven times the film's spring frequency, and semi-implicit Euler damps stably only while dt x rate < 2. A
// bound without it takes 15 substeps per frame here (dt x rate ~ 13: a particle went non-finite at 0.16 s when tried);
// with it (141), at the default safety, the stroke runs with no instability stop and the film, pushed towards the air's
// speed, never outruns the wands' peak by more than 4x.
TEST(Dynamics, TheExplicitBoundHoldsWithStrongAirCoupling) {
  Params p;
  p.particlesAtFullSolution = 200;
  p.integrator = 0;
  p.airPressureGain = 1000.0f;
  GestureOptions g;
  g.start = 0.0f;
  Simulation sim(p, WandTool{}, gestureAt(Gesture::Straight, g, 0.0));
  double fastest = 0;
  for (int f = 1; f <= 15; ++f) {
    try {
      sim.advanceFrame(gestureAt(Gesture::Straight, g, f * static_cast<double>(p.frameTime)));
    } catch (const SimulationUnstable& e) {
      FAIL() << e.what() << " (" << sim.substepsPerFrame() << " substeps per frame)";
    }
    fastest = std::max(fastest, sim.stats().maxSpeed);
  }
  std::printf("%d substeps per frame, fastest particle %.2f m/s\n", sim.substepsPerFrame(), fastest);
  EXPECT_LT(fastest, 4.0 * g.speed);
}

TEST(Dynamics, AFilmTooStiffForTheSubstepLimitIsRefusedWithAReason) {
  Params p;
  p.particlesAtFullSolution = 2000;
  p.filmInertia = 1e-5f;
  p.maxSubsteps = 50;
  p.integrator = 0;  // only the explicit reference has a stability bound
  try {
    Simulation sim(p, WandTool{}, restingWands());
    FAIL() << "accepted a film that needs more substeps than allowed";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("substeps per frame"), std::string::npos) << e.what();
  }
}

TEST(Dynamics, WandsFarApartOrTogetherStillGiveFiniteFrames) {
  // Absurd input (the tips far beyond the string, then on top of each other) must not produce NaN.
  Params p;
  p.particlesAtFullSolution = 300;
  Simulation sim(p, WandTool{}, restingWands());
  WandState apart = restingWands();
  apart.leftPosition.x() = -3.0f;
  apart.rightPosition.x() = 3.0f;
  WandState together = restingWands();
  together.leftPosition = together.rightPosition;
  for (const WandState& w : {apart, together}) {
    const StepUniforms u = sim.uniformsFor(w, w, 0.001f);
    for (float uu : {0.0f, 0.5f, 1.0f, 1.5f}) EXPECT_TRUE(wirePoint(wireNextOf(u), uu).allFinite());
    EXPECT_TRUE(std::isfinite(u.airVolume));
  }
}

}  // namespace
}  // namespace gb
