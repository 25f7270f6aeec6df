// The physical tension model (tensionModel 1) against soap-film physics: flat discs, Young-Laplace, catenoids.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "cpu_stepper.h"
#include "simulation.h"

namespace gb {
namespace {

Params physical(int particles) {
  Params p;
  p.tensionModel = 1;
  p.gravityY = 0.0f;  // the experiments are about tension alone
  p.particlesAtFullSolution = particles;
  return p;
}

// The neck: the smallest distance of a particle from the z axis through `center` (on a catenoid r = a cosh(z/a)
// >= a, within (dz / a)^2 / 2 of a for the row nearest the middle, dz <= half a row: 0.2% here).
double neckRadius(const Film& film, const Vec3& center) {
  double neck = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < film.state.size(); ++i) {
    const Vec3 d = film.state.position.get(i) - center;
    neck = std::min(neck, std::hypot(static_cast<double>(d.x()), static_cast<double>(d.y())));
  }
  return neck;
}

// The larger neck radius a of the catenoid r = a cosh(z / a) through rings of radius R at z = +-d/2:
// R = a cosh(d / (2a)), by bisection on the stable branch (a above the fold).
double catenoidNeck(double R, double d) {
  auto f = [&](double a) { return a * std::cosh(d / (2 * a)) - R; };
  double lo = 0.5523 * d, hi = R;  // the fold is at a = d / (2 x 1.1997): f < 0 there for d < 1.3255 R
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(PhysicalTension, AFilmOnAFlatRingRelaxesToAFlatDisc) {
  const Params p = physical(800);
  WandTool ring;
  ring.kind = ToolKind::Ring;
  WandState wands;
  wands.rightPosition = Vec3(0, 1.5f, 0);
  Simulation sim(p, ring, wands);
  State& s = sim.film().state;
  for (size_t i = 0; i < s.size(); ++i) {  // a 3 cm bump out of the plane
    const float r2 = (s.position.get(i) - wands.rightPosition).squaredNorm() / (ring.ringRadius * ring.ringRadius);
    if (!sim.film().topology.boundary[i]) s.position.z[i] += 0.03f * std::max(0.0f, 1.0f - r2);
  }
  sim.stepper().load(p, sim.film());
  for (int f = 0; f < 50; ++f) sim.advanceFrame(wands);  // 1 s
  double worst = 0;
  for (size_t i = 0; i < s.size(); ++i) worst = std::max(worst, static_cast<double>(std::abs(sim.film().state.position.z[i])));
  std::printf("flat disc: worst out-of-plane %.2e m after 1 s (bump 3e-2 m), %d substeps per frame\n", worst,
              sim.substepsPerFrame());
  EXPECT_LT(worst, 0.05 * 0.03) << "tension alone flattens a film on a flat ring (5% of the bump left at most)";
}

// Mean |H| R over the free particles: |grad A_i| / (2 A_i) is the discrete mean curvature (|areaTensionForce|
// divided by the tension and twice the Voronoi area).
double meanCurvatureTimes(const Simulation& sim, float length) {
  const Film& film = sim.film();
  double sum = 0;
  int count = 0;
  for (size_t i = 0; i < film.state.size(); ++i) {
    if (film.topology.boundary[i] || film.state.voronoiArea[i] <= 0) continue;
    const double gradient = areaTensionForce(film.topology, film.state, i).norm() / film.state.elasticity[i];
    sum += gradient / (2.0 * film.state.voronoiArea[i]) * length;
    ++count;
  }
  return sum / count;
}

// A film on a saddle-shaped wire (a ring bent to z = h cos(2 phi)) relaxes to a minimal surface: its mean
// curvature goes to near zero, from the curvature the bent wire first gives the film next to it.
TEST(PhysicalTension, AFilmOnABentWireRelaxesToAMinimalSurface) {
  const Params p = physical(800);
  WandTool ring;
  ring.kind = ToolKind::Ring;
  WandState wands;
  wands.rightPosition = Vec3(0, 1.5f, 0);
  Simulation sim(p, ring, wands);
  Film& film = sim.film();
  const float a = ring.ringRadius, h = 0.3f * a;
  for (size_t i = 0; i < film.state.size(); ++i) {
    if (!film.topology.boundary[i]) continue;
    const Vec3 d = film.state.position.get(i) - wands.rightPosition;
    film.state.position.z[i] += h * std::cos(2.0f * std::atan2(d.y(), d.x()));
    film.state.frameParam[i] = -1.0f;  // pinned on the bent wire
  }
  CpuStepper::refreshGeometry(p, film);
  sim.stepper().load(p, film);
  const double before = meanCurvatureTimes(sim, a);
  for (int f = 0; f < 100; ++f) sim.advanceFrame(wands);  // 2 s
  CpuStepper::refreshGeometry(p, sim.film());
  const double after = meanCurvatureTimes(sim, a);
  std::printf("minimal surface: mean |H| a = %.4f at first, %.4f after 2 s\n", before, after);
  // A saddle of height 0.3 a has principal curvatures ~ 2 h / a^2 = 0.6 / a: "near zero" is under 2% of that.
  EXPECT_LT(after, 0.012);
  EXPECT_LT(after, 0.1 * before);
}

TEST(PhysicalTension, ABubbleSettlesWhereYoungLaplaceSays) {
  const Params p = physical(1000);
  const Vec3 c(0, 1.5f, 0);
  Simulation sim(p, generateSphere(p, c, 0.4f, 3), WandState{});
  for (int f = 0; f < 50; ++f) sim.advanceFrame(WandState{});  // 1 s
  const Film& film = sim.film();
  double radius = 0, tension = 0;
  for (size_t i = 0; i < film.state.size(); ++i) {
    radius += (film.state.position.get(i) - centroid(film.state)).norm() / static_cast<double>(film.state.size());
    tension += film.state.elasticity[i] / static_cast<double>(film.state.size());  // 2 gamma (N/m)
  }
  const double excess = sim.lastPressure() - p.pressureCoefficient;
  const double laplace = 2.0 * tension / radius;  // 4 gamma / R: two surfaces
  std::printf("Young-Laplace: R = %.4f m, 2 gamma = %.4f N/m, dP = %.4f Pa, 4 gamma / R = %.4f Pa\n", radius,
              tension, excess, laplace);
  EXPECT_NEAR(excess, laplace, 0.02 * laplace) << "the issue's bound: 2%";
}

TEST(PhysicalTension, ACatenoidBetweenRingsOneRadiusApartHasTheAnalyticNeck) {
  const Params p = physical(1000);
  const float R = 0.3f, d = R;
  const Vec3 c(0, 1.5f, 0);
  Simulation sim(p, generateTube(p, c, R, d, 64), WandState{});
  for (int f = 0; f < 100; ++f) sim.advanceFrame(WandState{});  // 2 s
  const double neck = neckRadius(sim.film(), c);
  const double expected = catenoidNeck(R, d);
  std::printf("catenoid d = R: neck %.4f m, analytic %.4f m (%.4f R)\n", neck, expected, expected / R);
  EXPECT_NEAR(neck, expected, 0.02 * expected) << "the issue's bound: 2%";
}

// The neck radius of a tube between rings of radius R, d apart, after `seconds` of relaxing; 0 once it has
// pinched to under a tenth of R (the film has split into two discs).
double neckAfter(float R, float d, double seconds) {
  const Params p = physical(1000);
  const Vec3 c(0, 1.5f, 0);
  Simulation sim(p, generateTube(p, c, R, d, 48), WandState{});
  double neck = R;
  for (int f = 0; f < std::lround(seconds / p.frameTime) && neck > 0.1 * R; ++f) {
    sim.advanceFrame(WandState{});
    neck = neckRadius(sim.film(), c);
  }
  return neck > 0.1 * R ? neck : 0.0;
}

TEST(PhysicalTension, ACatenoidCollapsesPastTheCriticalSeparationFoundByBisection) {
  const float R = 0.3f;
  // Stable catenoids keep a neck above 0.55 R (the fold's neck is 0.5524 x 1.3255 R = 0.73 R); a film past the
  // critical separation thins to nothing. 3 s lets one just past it fall below 0.4 R.
  auto collapses = [&](float d) { return neckAfter(R, d, 3.0) < 0.4 * R; };
  EXPECT_TRUE(collapses(1.45f * R)) << "at d = 1.45 R there is no catenoid: two discs";
  float stable = 1.0f * R, collapsing = 1.45f * R;
  for (int it = 0; it < 4; ++it) {
    const float mid = 0.5f * (stable + collapsing);
    (collapses(mid) ? collapsing : stable) = mid;
  }
  const float critical = 0.5f * (stable + collapsing);
  std::printf("catenoid: critical separation %.4f R (analytic 1.3255 R), bracket [%.4f, %.4f] R\n", critical / R,
              stable / R, collapsing / R);
  EXPECT_NEAR(critical / R, 1.3255, 0.03 * 1.3255) << "the issue's bound: 3%";
}

// Transverse waves on a flat film travel at c = sqrt(T / (rho h)) = sqrt(2 gamma / (rho h)). A film on a ring
// of radius a started in its fundamental shape J0(2.405 r / a) oscillates at omega = 2.405 c / a; its period,
// from the zero crossings of the middle's displacement, gives c. Air drag and edge damping are off, so the
// wave keeps its speed (the drag of still air would slow it).
TEST(PhysicalTension, WavesOnAFlatFilmTravelAtTheCapillarySpeed) {
  Params p = physical(1200);
  p.airDrag = 0.0f;
  p.springDamping = 0.0f;
  p.frameTime = 0.005f;  // ~45 samples per period
  WandTool ring;
  ring.kind = ToolKind::Ring;
  WandState wands;
  wands.rightPosition = Vec3(0, 1.5f, 0);
  Simulation sim(p, ring, wands);
  State& s = sim.film().state;
  const float a = ring.ringRadius;
  size_t middle = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const float r = (s.position.get(i) - wands.rightPosition).norm();
    if (r < (s.position.get(middle) - wands.rightPosition).norm()) middle = i;
    if (!sim.film().topology.boundary[i]) s.position.z[i] += 0.002f * std::cyl_bessel_j(0.0f, 2.405f * std::min(r / a, 1.0f));
  }
  sim.stepper().load(p, sim.film());
  std::vector<double> crossings;  // times the middle passes z = 0 going down
  float previous = sim.film().state.position.z[middle];
  for (int f = 1; f <= 400 && crossings.size() < 4; ++f) {
    sim.advanceFrame(wands);
    const float z = sim.film().state.position.z[middle];
    if (previous > 0 && z <= 0) crossings.push_back(p.frameTime * (static_cast<float>(f - 1) + previous / (previous - z)));
    previous = z;
  }
  ASSERT_GE(crossings.size(), 3u) << "the film must oscillate";
  const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double measured = (2.0 * 3.14159265358979 / period) * a / 2.405;
  const double tension = 2.0 * p.surfaceTension;  // the film keeps its thickness: gamma_0
  const double expected = std::sqrt(tension / (p.liquidDensity * initialThickness(p)));
  std::printf("waves: period %.4f s, speed %.3f m/s, sqrt(2 gamma / (rho h)) = %.3f m/s\n", period, measured, expected);
  EXPECT_NEAR(measured, expected, 0.10 * expected) << "the issue's bound: 10%";
}

// Taylor-Culick on a whole bubble: a 1 um bubble of radius 1 m poked at its top is gone when the hole's rim
// has run half way round, "about" pi R / V after the poke (V = sqrt(2 gamma / (rho h))). Bound 25%, chosen
// and measured here (0.36 s against 0.444 s: 19% early): besides the hole front, which runs at V along mesh
// edges (slower than great circles), the torn film retracts under its full tension with nothing to slow it,
// since the model puts no mass into the rim that a real bursting film collects; that pulls the film towards
// the front. docs/validation.md reports it.
TEST(PhysicalTension, AOneMetreBubbleVanishesInPiROverV) {
  Params p = physical(1000);
  p.areaWeight = 0.01f;  // initial thickness 1 um
  Simulation sim(p, generateSphere(p, Vec3(0, 2.0f, 0), 1.0f, 4), WandState{});
  sim.startBurst(sim.topParticle());
  const double start = sim.time();
  double gone = -1;
  for (int f = 0; f < 200 && gone < 0; ++f) {
    sim.advanceFrame(WandState{});
    if (sim.lastEvents().finished) gone = sim.time() - start;
  }
  const double v = std::sqrt(2.0 * p.surfaceTension / (p.liquidDensity * 1e-6));
  const double expected = 3.14159265358979 * 1.0 / v;
  std::printf("bubble burst: gone after %.3f s, pi R / V = %.3f s\n", gone, expected);
  ASSERT_GT(gone, 0.0) << "the bubble must burst completely";
  EXPECT_NEAR(gone, expected, 0.25 * expected);
}

}  // namespace
}  // namespace gb
