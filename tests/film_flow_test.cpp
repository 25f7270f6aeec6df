// The thin-film flow (cpu-reference/stages/stages.h, docs/model.md "Film flow"): each term of the liquid's velocity
// against a hand-computed value, the flux of an edge, the lubrication limit on a tilted film, Marangoni relaxation
// of a surfactant step, conservation of liquid, evaporation, and the burst by thinning it leads to.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "stages/cpu_stepper.h"
#include "tests/test_films.h"
#include "topology/bursting.h"

namespace gb {
namespace {

constexpr float kPi = 3.14159265f;

double totalLiquid(const State& s) { return std::accumulate(s.liquid.begin(), s.liquid.end(), 0.0); }

// A flat sheet of equilateral triangles (side `spacing`), `columns` x `rows` particles, in the plane through the
// origin spanned by `right` and `up` (unit, orthogonal); row r is r spacing sqrt(3)/2 along `up`. Nothing holds its
// edges (no wire): the liquid flows freely to them.
Film makeSheet(const Params& p, int columns, int rows, float spacing, const Vec3& right, const Vec3& up) {
  std::vector<Vec3> positions;
  const float rowStep = spacing * std::sqrt(3.0f) / 2.0f;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c)
      positions.push_back((static_cast<float>(c) + 0.5f * static_cast<float>(r % 2)) * spacing * right +
                          static_cast<float>(r) * rowStep * up);
  const auto at = [&](int c, int r) { return static_cast<uint32_t>(r * columns + c); };
  std::vector<uint32_t> triangles;
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < columns; ++c) {
      if (r % 2 == 0) {
        triangles.insert(triangles.end(), {at(c, r), at(c + 1, r), at(c, r + 1)});
        triangles.insert(triangles.end(), {at(c + 1, r), at(c + 1, r + 1), at(c, r + 1)});
      } else {
        triangles.insert(triangles.end(), {at(c, r), at(c + 1, r + 1), at(c, r + 1)});
        triangles.insert(triangles.end(), {at(c, r), at(c + 1, r), at(c + 1, r + 1)});
      }
    }
  Film film = test::makeFilm(p, positions, triangles);
  film.topology.boundary.assign(positions.size(), 0u);
  return film;
}

// Sets every particle's liquid to `thickness` times its area, and the thickness the flow reads.
void setThickness(const Params& p, Film& film, float thickness) {
  CpuStepper::refreshGeometry(p, film);
  for (size_t i = 0; i < film.state.size(); ++i) film.state.liquid[i] = thickness * film.state.voronoiArea[i];
  CpuStepper::refreshGeometry(p, film);
}

// `steps` flow steps of `dt` on a film that does not move, the thickness refreshed after each as the film state
// stage does.
void flow(const Params& p, Film& film, int steps, float dt) {
  CpuStepper stepper;
  stepper.load(p, film);
  StepUniforms u;
  u.dt = dt;
  u.drainageDt = dt;
  for (int k = 0; k < steps; ++k) {
    stepper.runStage(Stage::FilmFlow, u);
    CpuStepper::refreshGeometry(p, film);
  }
}

// Only the term under test: no gravity, air, friction, viscosity or Marangoni stress unless a test sets it.
Params quietParams() {
  Params p;
  p.gravityY = 0.0f;
  p.airShear = 0.0f;
  p.surfaceRigidity = 0.0f;
  p.flowViscosity = 0.0f;
  p.marangoniElasticity = 0.0f;
  p.evaporationRate = 0.0f;
  return p;
}

TEST(FilmFlow, EachTermOfTheVelocityEquationAgainstHandValues) {
  // The regular hexagon of unit circumradius in z = 0 (normal +z): particle 0's ring is six neighbours at 1 m.
  Params p = quietParams();
  p.gravityX = 0.0f;
  p.gravityY = -3.0f;
  p.gravityZ = -4.0f;
  p.marangoniElasticity = 0.01f;
  p.flowViscosity = 0.002f;
  p.airShear = 0.005f;
  p.surfaceRigidity = 0.5f;
  Film film = test::makeHexagon(p);
  setThickness(p, film, 2e-6f);
  State& s = film.state;
  ASSERT_NEAR(s.normal.z[0], 1.0f, 1e-6f);
  const float a = 0.3f;  // ln Gamma = a x + const: the surfactant exp(a x) on a film of even thickness
  for (size_t i = 0; i < s.size(); ++i) s.surfactant[i] = std::exp(a * s.position.x[i]);
  for (size_t j = 1; j < s.size(); ++j) s.flowVelocity.set(j, Vec3(0.1f, -0.2f, 0.0f));
  s.airFlow.set(0, Vec3(0.6f, 0.0f, 0.9f));  // m^3/s over a 2 m^2 frame: air at (0.3, 0, 0.45) m/s
  s.velocity.set(0, Vec3(0.0f, 0.1f, 0.7f));
  StepUniforms u;
  u.wireArea = 2.0f;
  std::vector<float> logSurfactant(s.size());
  for (size_t i = 0; i < s.size(); ++i) filmFlowLogSurfactant(p, s, i, logSurfactant);
  const FilmFlowTerms t = filmFlowTerms(p, u, film.topology, s, 0, logSurfactant);
  const float rho = p.liquidDensity, e = 2e-6f;
  // g_t: gravity less its normal part.
  EXPECT_NEAR((t.gravity - Vec3(0, -3, 0)).norm(), 0.0f, 1e-6f);
  // grad ln Gamma = (2/6) sum_j a x_j d_j = (a, 0, 0) on the regular ring; the stress pulls towards low Gamma.
  const Vec3 marangoni(-p.marangoniElasticity / (rho * e) * a, 0, 0);
  EXPECT_NEAR((t.marangoni - marangoni).norm(), 1e-5f * marangoni.norm(), 1e-5f * marangoni.norm());
  // Air: the air's velocity past the film, (0.3, 0, 0.45) - (0, 0.1, 0.7), along the surface; rate 2 k_air / (rho e).
  EXPECT_NEAR((t.air - Vec3(0.3f, -0.1f, 0)).norm(), 0.0f, 1e-6f);
  EXPECT_NEAR(t.airRate, 2.0f * 0.005f / (rho * e), 1e-6f * t.airRate);
  // The surfaces' friction 12 mu phi / (rho e^2).
  EXPECT_NEAR(t.wallRate, 12.0f * 1e-3f * 0.5f / (rho * e * e), 1e-6f * t.wallRate);
  // Viscosity: (4/6) nu sum_j 1/|d|^2 = 4 nu; its pull 4 nu u_j.
  EXPECT_NEAR(t.viscosityRate, 4.0f * 0.002f, 1e-8f);
  EXPECT_NEAR((t.viscosityPull - 4.0f * 0.002f * Vec3(0.1f, -0.2f, 0)).norm(), 0.0f, 1e-8f);
}

TEST(FilmFlow, TheGradientsLogDifferencesKeepAFloatsPrecisionOnANearlyEvenFilm) {
  // ln Gamma is taken relative to a new film's (logSurfactant), of order one: the difference of two neighbours' is
  // within a few ulps of 1 of the exact ln of their ratio, however close the two are. (Taken in metres, about
  // ln 1e-6, each would round to half an ulp of 14, 4.8e-7, and a relative step of 1e-6 would be lost in it.)
  // Tolerance: 4 ulps of 1 (4.8e-7): each log rounds to half an ulp of its value (below 2) and logf adds under one,
  // and the product inside rounds by 2^-24 of the ratio.
  const Params p;
  const float e0 = initialThickness(p);
  for (float surfactant : {0.4f, 1.0f, 1.7f})
    for (float thickness : {0.3f * e0, e0, 2.5f * e0})
      for (float step : {1e-6f, 1e-5f, 1e-4f, 1e-3f, 1e-1f}) {
        const float thicker = thickness * (1.0f + step);
        const double exact = std::log(static_cast<double>(thicker) / static_cast<double>(thickness));
        const double difference = static_cast<double>(logSurfactant(p, surfactant, thicker)) -
                                  static_cast<double>(logSurfactant(p, surfactant, thickness));
        EXPECT_NEAR(difference, exact, 4.8e-7) << "surfactant " << surfactant << ", step " << step;
      }
}

TEST(FilmFlow, AnEdgesFluxIsWhatEachEndSendsAndExactlyAntisymmetric) {
  // The hexagon: particle k = 1..6 at angle (k - 1) 60 degrees on the unit circle; u_k = (0.2 - 0.1 k, 0.05, 0),
  // thickness (1 + 0.1 k) um, particle 6 may send only half of what its velocity sweeps (its limit).
  Params p = quietParams();
  Film film = test::makeHexagon(p);
  setThickness(p, film, 1e-6f);
  State& s = film.state;
  for (size_t i = 0; i < s.size(); ++i) {
    s.flowVelocityNext.set(i, Vec3(0.2f - 0.1f * static_cast<float>(i), 0.05f, 0));
    s.thickness[i] = 1e-6f * (1.0f + 0.1f * static_cast<float>(i));
    s.flowLimit[i] = i == 6 ? 0.5f : 1.0f;
    s.flowAreaShare[i] = flowAreaShare(film.topology, s, i);  // as pass 1 stores it
  }
  const float dt = 0.02f, h = std::sqrt(3.0f) / 2.0f;
  // Edge 0 -> 1, d = (1, 0, 0), dual length from the shares A_0 / 6 and A_1 / 3 (particle 1 has 3 springs): particle 0
  // sweeps u_0 . d = 0.2 of it; particle 1 sends with u_1 . (-d) = -0.1 < 0, i.e. nothing.
  const float dual1 = dt * 2.0f * (s.voronoiArea[0] / 6.0f + s.voronoiArea[1] / 3.0f);
  EXPECT_NEAR(filmFlowSweptArea(dt, s, 0, 1), dual1 * 0.2f, 1e-6f * dual1);
  EXPECT_EQ(filmFlowSweptArea(dt, s, 1, 0), 0.0f);
  EXPECT_NEAR(filmFlowEdgeFlux(dt, s, 0, 1), dual1 * 0.2f * 1e-6f, 1e-6f * dual1 * 1e-6f);
  // Edge 0 -> 6, d = (1/2, -sqrt(3)/2, 0): 0 sends with 0.1 - 0.05 h, 6 (u = (-0.4, 0.05, 0)) towards 0 with
  // 0.2 + 0.05 h, its thickness 1.6 um and its limit 0.5.
  const float dual6 = dt * 2.0f * (s.voronoiArea[0] / 6.0f + s.voronoiArea[6] / 3.0f);
  const float expected = dual6 * ((0.1f - 0.05f * h) * 1e-6f - (0.2f + 0.05f * h) * 1.6e-6f * 0.5f);
  EXPECT_NEAR(filmFlowEdgeFlux(dt, s, 0, 6), expected, 1e-5f * std::abs(expected));
  for (uint32_t j = 1; j < 7; ++j)  // bit for bit: what leaves one particle enters the other
    EXPECT_EQ(filmFlowEdgeFlux(dt, s, 0, j), -filmFlowEdgeFlux(dt, s, j, 0));
}

// The liquid's volume flux per width across the line between rows `row` and row + 1 of a sheet (m^2/s), over the
// columns away from its sides, from the last flow step's edge fluxes.
double fluxAcrossRow(const Film& film, int columns, int row, float dt) {
  const State& s = film.state;
  const Topology& topo = film.topology;
  double flux = 0;
  int counted = 0;
  for (int c = columns / 4; c < 3 * columns / 4; ++c) {
    const auto i = static_cast<uint32_t>((row + 1) * columns + c);  // the row above sends down
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
      const uint32_t j = topo.springNeighbour[k];
      if (static_cast<int>(j) / columns != row) continue;
      flux += filmFlowEdgeFlux(dt, s, i, j);
    }
    ++counted;
  }
  const float spacing = (s.position.get(1) - s.position.get(0)).norm();
  return flux / dt / (static_cast<double>(counted) * spacing);
}

TEST(FilmFlow, ATiltedFilmWithRigidSurfacesDrainsAsLubricationTheorySays) {
  // A film between immobile surfaces (phi = 1) on a plane 30 degrees from vertical: the liquid's mean velocity is
  // Poiseuille's, u = rho g_t e^2 / (12 mu), and the flux per width e u grows as e^3 (the lubrication scaling).
  Params p = quietParams();
  p.surfaceRigidity = 1.0f;
  const float tilt = 30.0f * kPi / 180.0f;
  p.gravityY = -9.81f;
  const Vec3 right(1, 0, 0), up(0, std::cos(tilt), std::sin(tilt));
  const int columns = 24, rows = 16;
  const float dt = 0.02f;
  double fluxes[2];
  for (int k = 0; k < 2; ++k) {
    const float e = k == 0 ? 1e-6f : 2e-6f;
    Film film = makeSheet(p, columns, rows, 0.01f, right, up);
    setThickness(p, film, e);
    flow(p, film, 3, dt);  // the friction's rate (12,000 1/s at 1 um) settles u within the first step
    const double gAlong = 9.81 * std::cos(tilt);
    const double expected = p.liquidDensity * gAlong * double(e) * e * e / (12.0 * p.liquidViscosity);
    fluxes[k] = fluxAcrossRow(film, columns, rows / 2, dt);
    std::printf("e = %.0e m: flux per width %.4e m^2/s, lubrication theory %.4e\n", e, fluxes[k], expected);
    // The flux across a row of a regular sheet is exact for a uniform flow (flowSweptArea's dual edges tile the
    // line); the velocity is the implicit update's fixed point, reached to 1 / (1 + dt rate)^3 < 1e-6: 1%
    // allows for the rows near the middle having thinned or thickened by float rounding only.
    EXPECT_NEAR(fluxes[k], expected, 0.01 * expected);
  }
  EXPECT_NEAR(fluxes[1] / fluxes[0], 8.0, 0.08) << "the lubrication flux grows as the thickness cubed";
}

TEST(FilmFlow, TheTopOfAVerticalFilmThinsAndTheBottomThickens) {
  // The default flow on a 40 cm vertical sheet, 5 s: the liquid runs down.
  Params p;
  const int columns = 20, rows = 24;
  Film film = makeSheet(p, columns, rows, 0.02f, Vec3(1, 0, 0), Vec3(0, 1, 0));
  const float e0 = 2e-6f;
  setThickness(p, film, e0);
  flow(p, film, 250, 0.02f);
  double top = 0, bottom = 0;
  for (int c = 0; c < columns; ++c) {
    top += film.state.thickness[static_cast<size_t>((rows - 1) * columns + c)] / columns;
    bottom += film.state.thickness[static_cast<size_t>(c)] / columns;
  }
  std::printf("after 5 s: top %.3g m, bottom %.3g m (from %.3g m)\n", top, bottom, e0);
  EXPECT_LT(top, 0.7 * e0);
  EXPECT_GT(bottom, 1.3 * e0);
}

TEST(FilmFlow, ASurfactantStepRelaxesByMarangoniFlow) {
  // A level film (gravity along its normal) with twice the surfactant on its left half: the tension is lower there,
  // and the Marangoni stress pulls liquid and surfactant over to the right until the step has smoothed out.
  Params p;
  p.gravityY = -9.81f;
  p.evaporationRate = 0.0f;  // saturated air: the liquid only flows
  const int columns = 24, rows = 12;
  Film film = makeSheet(p, columns, rows, 0.02f, Vec3(1, 0, 0), Vec3(0, 0, 1));
  setThickness(p, film, 2e-6f);
  State& s = film.state;
  const auto left = [&](size_t i) { return static_cast<int>(i) % columns < columns / 2; };
  for (size_t i = 0; i < s.size(); ++i) s.surfactant[i] = left(i) ? 2.0f : 1.0f;
  const auto contrast = [&] {  // mean ln Gamma, left less right
    double l = 0, r = 0;
    for (size_t i = 0; i < s.size(); ++i)
      (left(i) ? l : r) += std::log(double(s.surfactant[i]) * s.thickness[i]) / (0.5 * static_cast<double>(s.size()));
    return l - r;
  };
  const auto rightLiquid = [&] {
    double sum = 0;
    for (size_t i = 0; i < s.size(); ++i)
      if (!left(i)) sum += s.liquid[i];
    return sum;
  };
  const double contrastBefore = contrast(), rightBefore = rightLiquid(), total = totalLiquid(s);
  // 12 s: the capped Marangoni diffusion (kMarangoniCourant), slowed by the surfaces' friction, crosses the half-width
  // in seconds.
  const int steps = 600;
  flow(p, film, steps, 0.02f);
  std::printf("ln Gamma step %.3f -> %.3f, right half's liquid x %.3f\n", contrastBefore, contrast(),
              rightLiquid() / rightBefore);
  EXPECT_NEAR(contrastBefore, std::log(2.0), 1e-6);
  EXPECT_LT(contrast(), 0.5 * contrastBefore) << "the step relaxes";
  EXPECT_GT(contrast(), -0.05 * contrastBefore) << "without overshooting by more than 5% of the step";
  EXPECT_GT(rightLiquid(), 1.05 * rightBefore) << "liquid flows towards the higher tension";
  // Each step rounds each particle's liquid once (2^-24 relative at most).
  EXPECT_NEAR(totalLiquid(s), total, steps * 0x1p-24 * total);
}

// A vertical ring film under the whole default flow, with the wands' air blowing across it.
Film ringFilmInAMovingAir(const Params& p) {
  WandTool ring;
  ring.kind = ToolKind::Ring;
  Film film = generateFilm(p, ring, gestureAt(Gesture::Straight, GestureOptions{}, 0.0));
  CpuStepper::refreshGeometry(p, film);
  for (size_t i = 0; i < film.state.size(); ++i)
    film.state.airFlow.set(i, Vec3(0.05f * std::sin(7.0f * film.state.position.y[i]), 0.02f, 0.0f));
  return film;
}

TEST(FilmFlow, ConservesLiquidToFloatRounding) {
  // The ring film in saturated air, 10 s: liquid only moves. Each step rounds each particle's new liquid once (at
  // most 2^-24 relative), so after N steps the total is within N 2^-24 of where it started; a flux that is not
  // exactly antisymmetric loses far more.
  Params p;
  p.particlesAtFullSolution = 1500;
  p.evaporationRate = 0.0f;
  Film film = ringFilmInAMovingAir(p);
  const double before = totalLiquid(film.state);
  const int steps = 500;
  flow(p, film, steps, 0.02f);
  const double after = totalLiquid(film.state);
  std::printf("liquid %.9g -> %.9g m^3 (relative %.2e)\n", before, after, (after - before) / before);
  EXPECT_NEAR(after, before, steps * 0x1p-24 * before);
  for (size_t i = 0; i < film.state.size(); ++i) {
    ASSERT_GE(film.state.liquid[i], 0.0f) << "the limiter keeps every particle's liquid";
    ASSERT_TRUE(std::isfinite(film.state.surfactant[i]));
  }
}

TEST(FilmFlow, TheGatherSendsWhatEachEndsSweptAreaSends) {
  // Pass 3 reads each edge's two swept areas as pass 2 kept them, by spring and end: every particle's new liquid must
  // be, bit for bit, its liquid less what it sends (filmFlowSent, the swept area computed again) plus what each
  // neighbour sends it, in its ring's order, on a flowing film in saturated air.
  Params p;
  p.particlesAtFullSolution = 1500;
  p.evaporationRate = 0.0f;
  Film film = ringFilmInAMovingAir(p);
  flow(p, film, 20, 0.02f);  // the liquid under way, the thickness no longer uniform
  State& s = film.state;
  const Topology& topo = film.topology;
  StepUniforms u;
  u.dt = u.drainageDt = 0.02f;
  std::vector<float> logSurfactant(s.size()), swept(2 * topo.springCount());
  for (size_t i = 0; i < s.size(); ++i) filmFlowLogSurfactant(p, s, i, logSurfactant);
  for (size_t i = 0; i < s.size(); ++i) filmFlowVelocity(p, u, topo, s, i, logSurfactant);
  for (size_t i = 0; i < s.size(); ++i) filmFlowLimit(p, u.drainageDt, topo, s, i, swept);
  const State before = s;
  for (size_t j = 0; j < s.size(); ++j) filmFlowGather(p, u.drainageDt, topo, s, j, swept);
  int flowing = 0;
  for (uint32_t j = 0; j < s.size(); ++j) {
    float out = 0.0f;
    for (uint32_t k = topo.springOffset[j]; k < topo.springOffset[j + 1]; ++k) {
      const uint32_t i = topo.springNeighbour[k];
      out += filmFlowSent(u.drainageDt, before, j, i) - filmFlowSent(u.drainageDt, before, i, j);
    }
    ASSERT_EQ(s.liquid[j], before.liquid[j] - out) << "particle " << j;
    flowing += out != 0.0f;
  }
  EXPECT_GT(flowing, static_cast<int>(s.size()) / 2) << "most particles send or receive liquid";
}

TEST(FilmFlow, EvaporationTakesItsRateTimesTheAreaWhileTheFlowMovesTheRest) {
  // The same ring film flowing in dry air (the default evaporation), 2 s, no particle near black film (where
  // evaporation stops): what is lost is exactly rate x time x area, the flow moves the rest, and evaporation
  // leaves the surfactant behind (its total, surfactant per liquid times liquid, is kept). Rounding as above, twice
  // per step (the flow's and evaporation's).
  Params p;
  p.particlesAtFullSolution = 1500;
  ASSERT_GT(p.evaporationRate, 0.0f) << "the default air is dry";
  Film film = ringFilmInAMovingAir(p);
  const State& s = film.state;
  const auto totalSurfactant = [&] {
    double sum = 0;
    for (size_t i = 0; i < s.size(); ++i) sum += double(s.surfactant[i]) * s.liquid[i];
    return sum;
  };
  const double area = std::accumulate(s.voronoiArea.begin(), s.voronoiArea.end(), 0.0);
  const double before = totalLiquid(s), surfactantBefore = totalSurfactant();
  const int steps = 100;
  const float dt = 0.02f;
  flow(p, film, steps, dt);
  const double lost = before - totalLiquid(s), expected = double(p.evaporationRate) * steps * dt * area;
  std::printf("evaporated %.6g m^3, rate x time x area %.6g m^3 (%.1f%% of the liquid)\n", lost, expected,
              100 * expected / before);
  ASSERT_GT(*std::min_element(s.thickness.begin(), s.thickness.end()), 10 * p.blackFilmThickness)
      << "no particle came near black film";
  EXPECT_NEAR(lost, expected, 2 * steps * 0x1p-24 * before);
  EXPECT_NEAR(totalSurfactant(), surfactantBefore, 2 * steps * 0x1p-24 * surfactantBefore);
}

TEST(FilmFlow, EvaporationStopsAtBlackFilm) {
  // A level film 0.3 um thick in dry air with no flow: it thins at the evaporation rate, 2 s to black film, and
  // stays black film (the few nanometres of a black film hold too little water to lose more).
  Params p = quietParams();
  p.evaporationRate = 1.5e-7f;
  Film film = makeSheet(p, 8, 8, 0.02f, Vec3(1, 0, 0), Vec3(0, 0, 1));
  setThickness(p, film, 0.3e-6f);
  flow(p, film, 50, 0.02f);  // 1 s: 0.15 um gone
  for (size_t i = 0; i < film.state.size(); ++i)
    ASSERT_NEAR(film.state.thickness[i], 0.15e-6f, 1e-4f * 0.15e-6f) << "thins at the rate, particle " << i;
  flow(p, film, 100, 0.02f);  // 2 s more: would be 0.15 um under zero
  for (size_t i = 0; i < film.state.size(); ++i)
    ASSERT_NEAR(film.state.thickness[i], p.blackFilmThickness, 1e-5f * p.blackFilmThickness) << "particle " << i;
}

TEST(FilmFlow, DrainageStopsAtBlackFilm) {
  // No Marangoni stress and slippery surfaces: the top of a vertical sheet drains fast, down to the black film's
  // thickness and no further (the limiter leaves e_b A_Vor), whatever the flow.
  Params p;
  p.marangoniElasticity = 0.0f;
  p.surfaceRigidity = 0.0f;
  const int columns = 12, rows = 14;
  Film film = makeSheet(p, columns, rows, 0.02f, Vec3(1, 0, 0), Vec3(0, 1, 0));
  setThickness(p, film, 1e-6f);
  flow(p, film, 200, 0.02f);
  float thinnest = 1.0f;
  for (size_t i = 0; i < film.state.size(); ++i) thinnest = std::min(thinnest, film.state.thickness[i]);
  std::printf("thinnest after 4 s: %.1f nm (black film %.0f nm)\n", 1e9 * thinnest, 1e9 * p.blackFilmThickness);
  // The limiter leaves each particle at least e_b times its area at the step's start; the film does not move, so to
  // float rounding (1e-6 relative covers a few roundings of the liquid and the area).
  EXPECT_GE(thinnest, p.blackFilmThickness * (1.0f - 1e-6f));
  EXPECT_LT(thinnest, 1.25f * p.blackFilmThickness) << "the top drained to black film";
}

TEST(FilmFlow, AFilmDrainedThinBurstsByThinning) {
  // Without the black film's floor (e_b = 0), no Marangoni stress and slippery surfaces: the top of a vertical sheet
  // drains to nothing, and Algorithm 3's thickness test cracks it there, from the simulated thickness.
  Params p;
  p.marangoniElasticity = 0.0f;
  p.surfaceRigidity = 0.0f;
  p.blackFilmThickness = 0.0f;
  const int columns = 12, rows = 14;
  Film film = makeSheet(p, columns, rows, 0.02f, Vec3(1, 0, 0), Vec3(0, 1, 0));
  setThickness(p, film, 1e-6f);
  BurstFront front;
  Aerosol aerosol;
  double now = 0;
  for (int k = 0; k < 500 && front.cause == nullptr; ++k) {
    flow(p, film, 1, 0.02f);
    now += 0.02;
    advanceBurst(p, now, film, front, aerosol);
  }
  ASSERT_NE(front.cause, nullptr) << "the drained film never burst";
  EXPECT_STREQ(front.cause, "thin");
  std::printf("burst by thinning after %.2f s\n", now);
}

}  // namespace
}  // namespace gb
