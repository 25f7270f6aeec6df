// The physical tension model (tensionModel 1) against soap-film physics (docs/validation.md). Each experiment
// (cpu-reference/simulation/experiments.cpp) measures one number; the bounds are the required ones unless the comment
// says why.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "model/film.h"
#include "simulation/experiments.h"
#include "solver/implicit_euler.h"
#include "stages/stages.h"
#include "tests/test_films.h"

namespace gb {
namespace {

Measurement measure(const std::string& name, int particles) {
  Params p;
  p.particlesAtFullSolution = particles;
  const Measurement m = runExperiment(name, p);
  std::printf("%s: %s = %.6g %s (analytic %.6g, %s)\n", m.experiment.c_str(), m.quantity.c_str(), m.measured,
              m.unit.c_str(), m.analytic, m.law.c_str());
  return m;
}

TEST(PhysicalTension, AFilmOnAFlatRingRelaxesToAFlatDisc) {
  // Tension alone flattens a 3 cm bump: 5% of it left at most after 1 s.
  EXPECT_LT(measure("flat-disc", 800).measured, 0.05 * 0.03);
}

TEST(PhysicalTension, AFilmOnABentWireRelaxesToAMinimalSurface) {
  // A saddle of height 0.3 a has curvatures ~ 2 h / a^2 = 0.6 / a: "near zero" is under 2% of that. The film starts
  // as z = h (r/a)^4 cos 2 theta, whose mean curvature 6 h r^2 cos 2 theta / a^4 averages |H| a ~ 0.57.
  // The experiment throws if the film burst and left nothing to measure (it once passed that way).
  EXPECT_LT(measure("minimal-surface", 800).measured, 0.012);
}

TEST(PhysicalTension, ACatenoidBetweenRingsOneRadiusApartHasTheAnalyticNeck) {
  const Measurement m = measure("catenoid", 1000);
  EXPECT_NEAR(m.analytic / 0.3, 0.8483, 1e-3) << "the analytic neck itself (0.8483 R)";
  EXPECT_NEAR(m.measured, m.analytic, 0.02 * m.analytic);
}

TEST(PhysicalTension, ACatenoidCollapsesPastTheCriticalSeparationFoundByBisection) {
  // The experiment fails (throws) if the film at 1.45 R does not collapse into two discs.
  const Measurement m = measure("catenoid-critical", 1000);
  EXPECT_NEAR(m.measured, 1.3255, 0.03 * 1.3255);
}

TEST(PhysicalTension, ABubbleSettlesWhereYoungLaplaceSays) {
  const Measurement m = measure("young-laplace", 1000);
  EXPECT_NEAR(m.measured, m.analytic, 0.02 * m.analytic);
}

TEST(PhysicalTension, WavesOnAFlatFilmTravelAtTheCapillarySpeed) {
  const Measurement m = measure("waves", 1200);
  EXPECT_NEAR(m.measured, m.analytic, 0.10 * m.analytic);
}

// "About" pi R / V; bound 25%, chosen and measured here (0.36 s against 0.444 s: 19% early): besides the hole
// front, which runs at V along mesh edges (slower than great circles), the torn film retracts under its full
// tension with nothing to slow it, since the model puts no mass into the rim that a real bursting film
// collects. docs/validation.md reports it.
TEST(PhysicalTension, AOneMetreBubbleVanishesInPiROverV) {
  const Measurement m = measure("bubble-burst", 1000);
  EXPECT_NEAR(m.measured, m.analytic, 0.25 * m.analytic);
}

// The tension's potential is the energy whose slope dW/da is the tension 2 gamma the step applies, at every area:
// below the clamp (gamma at gamma_0 / 2), where gamma follows the Gibbs law, and above it (2 gamma_0). Central
// differences of 0.01% of the area in double precision; bound 1e-4 of 2 gamma_0, for the float thickness that
// filmTension takes (its rounding moves gamma by E_G / 2 x 6e-8). And it is not 2 gamma a: where gamma follows the
// area, W grows by 2 gamma da, 2 gamma a by E_G da more.
TEST(PhysicalTension, TheTensionsPotentialHasTheTensionAsItsSlope) {
  Params p;
  const float liquid = 1e-6f;  // m^3: 0.2 m^2 of film at the dip thickness
  const double dipArea = liquid / initialThickness(p);
  for (double area :
       {0.02 * dipArea, 0.2 * dipArea, 0.5 * dipArea, dipArea, 3.0 * dipArea, 8.0 * dipArea, 20.0 * dipArea}) {
    const double da = 1e-4 * area;
    const double slope =
        (filmTensionEnergy(p, liquid, area + da) - filmTensionEnergy(p, liquid, area - da)) / (2.0 * da);
    const double tension = filmTension(p, static_cast<float>(liquid / area));
    EXPECT_NEAR(slope, tension, 1e-4 * 2.0 * p.surfaceTension) << "area " << area / dipArea << " x the dip's";
  }
  const double a = 2.0 * dipArea, da = 1e-3 * a;
  const double potentialGain = filmTensionEnergy(p, liquid, a + da) - filmTensionEnergy(p, liquid, a);
  const double naiveGain = filmTension(p, static_cast<float>(liquid / (a + da))) * (a + da) -
                           filmTension(p, static_cast<float>(liquid / a)) * a;
  EXPECT_NEAR(naiveGain - potentialGain, p.gibbsElasticity * da, 0.01 * p.gibbsElasticity * da);
}

// Drainage moves liquid between particles, not surfactant: a particle that lost half its liquid is half as thick
// (its colour, its bursting) but pulls as before, its surfactant per area unchanged; stretched by 20% it pulls harder
// by E_G ln 1.2 (Gibbs). Bound 1e-6 of 2 gamma_0: float rounding of the logarithm's argument (E_G / 2 x 1.2e-7 a
// step) over the few operations of filmTension.
TEST(PhysicalTension, DrainageThinsTheFilmButLeavesItsTension) {
  Params p;
  p.tensionModel = 1;
  Film film = test::makeHexagon(p);
  State& s = film.state;
  const float liquid = 1e-9f;  // m^3
  s.liquid[0] = liquid;
  s.mass[0] = particleMass(p, 0.0f, liquid);  // made with this liquid
  s.voronoiArea[0] = 1.5f * liquid / initialThickness(p);
  filmState(p, 0.0f, s, 0);
  const float tension = s.elasticity[0], thickness = s.thickness[0];
  ASSERT_GT(tension, 2.0f * p.surfaceTension) << "stretched 1.5 times: the Gibbs law, not its clamp";
  ASSERT_LT(tension, 4.0f * p.surfaceTension);

  s.liquid[0] = 0.5f * liquid;  // drained
  filmState(p, 0.0f, s, 0);
  EXPECT_NEAR(s.thickness[0], 0.5f * thickness, 1e-6f * thickness);
  EXPECT_NEAR(s.elasticity[0], tension, 1e-6f * 2.0f * p.surfaceTension) << "drainage moved no surfactant";

  s.voronoiArea[0] *= 1.2f;  // stretched
  filmState(p, 0.0f, s, 0);
  EXPECT_NEAR(s.elasticity[0], tension + p.gibbsElasticity * std::log(1.2f), 1e-6f * 2.0f * p.surfaceTension);
}

// Within a step a triangle's gamma follows Gibbs's law in its own area (triangleTensionAt): at its start area it
// pulls with the tension it started with, stretched 20% harder by E_G ln 1.2, and never beyond filmTension's clamps;
// triangleTensionEnergy is its potential. Slope bound 1e-4 of 2 gamma_0, as for the particle's potential above.
TEST(PhysicalTension, ATrianglesTensionEnergyHasItsTensionAsItsSlope) {
  Params p;
  const float startTension = 2.2f * p.surfaceTension, startArea = 1e-4f;  // N/m, m^2
  EXPECT_EQ(triangleTensionAt(p, startTension, startArea, startArea), startTension);
  EXPECT_NEAR(triangleTensionAt(p, startTension, startArea, 1.2f * startArea),
              startTension + p.gibbsElasticity * std::log(1.2f), 1e-6f * 2.0f * p.surfaceTension);
  EXPECT_EQ(triangleTensionAt(p, startTension, startArea, 100.0f * startArea), 4.0f * p.surfaceTension);
  EXPECT_EQ(triangleTensionAt(p, startTension, startArea, 0.01f * startArea), p.surfaceTension);
  EXPECT_NEAR(triangleTensionEnergy(p, startTension, startArea, startArea), startTension * startArea,
              1e-7 * startTension * startArea);
  for (double stretch : {0.01, 0.1, 0.5, 0.9, 1.0, 1.1, 2.0, 10.0, 100.0}) {
    const double area = stretch * startArea, da = 1e-4 * area;
    const double slope = (triangleTensionEnergy(p, startTension, startArea, area + da) -
                          triangleTensionEnergy(p, startTension, startArea, area - da)) /
                         (2.0 * da);
    EXPECT_NEAR(slope, triangleTensionAt(p, startTension, startArea, static_cast<float>(area)),
                1e-4 * 2.0 * p.surfaceTension)
        << "stretched " << stretch << " times";
  }
}

TEST(PhysicalTension, AnUnknownExperimentIsNamed) {
  EXPECT_THROW(runExperiment("soap-opera", Params{}), std::invalid_argument);
}

}  // namespace
}  // namespace gb
