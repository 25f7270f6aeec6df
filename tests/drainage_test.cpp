// Position-dependent drainage, Eqs. (14)-(15): conservation, direction, and the Sticky parameter.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "capture/scripted_gestures.h"
#include "simulation/simulation.h"
#include "stages/cpu_stepper.h"

namespace gb {
namespace {

double totalLiquid(const State& s) { return std::accumulate(s.liquid.begin(), s.liquid.end(), 0.0); }

// A vertical ring film (gravity in its plane) drained for `seconds` with nothing else moving.
Film drainedRingFilm(Params p, float seconds) {
  p.particlesAtFullSolution = 1500;
  WandTool ring;
  ring.kind = ToolKind::Ring;
  Film film = generateFilm(p, ring, gestureAt(Gesture::Straight, GestureOptions{}, 0.0));
  CpuStepper stepper;
  stepper.load(p, film);
  StepUniforms u;
  u.dt = 0.01f;
  u.drainageDt = 0.01f;
  for (int k = 0; k < static_cast<int>(seconds / u.dt); ++k) stepper.runStage(Stage::Drainage, u);
  CpuStepper::refreshGeometry(p, film);
  return film;
}

// Mean thickness of the particles in the top and bottom tenth of the film's height.
std::pair<double, double> topAndBottomThickness(const Film& film) {
  const State& s = film.state;
  float lo = 1e9f, hi = -1e9f;
  for (size_t i = 0; i < s.size(); ++i) {
    lo = std::min(lo, s.position.y[i]);
    hi = std::max(hi, s.position.y[i]);
  }
  double top = 0, bottom = 0;
  int nt = 0, nb = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const float h = (s.position.y[i] - lo) / (hi - lo);
    if (h > 0.9f) top += s.thickness[i], ++nt;
    if (h < 0.1f) bottom += s.thickness[i], ++nb;
  }
  return {top / nt, bottom / nb};
}

TEST(Drainage, ConservesLiquid) {
  Params p;
  const Film before = drainedRingFilm(p, 0.0f);
  const Film after = drainedRingFilm(p, 10.0f);  // 1000 steps
  // Each step rounds every particle's new liquid once (~6e-8 relative); over 1000 steps of 1500 particles
  // the total drifts far less than 1e-5 relative unless liquid is created or lost.
  EXPECT_NEAR(totalLiquid(after.state), totalLiquid(before.state), 1e-5 * totalLiquid(before.state));
}

TEST(Drainage, TopThinsAndBottomThickensUnderGravity) {
  Params p;
  const auto [top, bottom] = topAndBottomThickness(drainedRingFilm(p, 20.0f));
  const double e0 = initialThickness(p);
  std::printf("after 20 s: top %.3g m, bottom %.3g m, initial %.3g m\n", top, bottom, e0);
  EXPECT_LT(top, 0.7 * e0) << "the top must drain (Figure 8)";
  EXPECT_GT(bottom, 1.3 * e0) << "the bottom must thicken (Figure 8)";
  // Gravity upside down: the other way round.
  p.gravityY = 9.81f;
  const auto [topUp, bottomUp] = topAndBottomThickness(drainedRingFilm(p, 20.0f));
  EXPECT_GT(topUp, 1.3 * e0);
  EXPECT_LT(bottomUp, 0.7 * e0);
}

TEST(Drainage, LargerStickyDelaysDrainage) {
  Params thin, thick;
  thin.sticky = 20.0f;
  thick.sticky = 30.0f;
  const double topThin = topAndBottomThickness(drainedRingFilm(thin, 5.0f)).first;
  const double topThick = topAndBottomThickness(drainedRingFilm(thick, 5.0f)).first;
  EXPECT_GT(topThick, topThin) << "a more viscous solution must keep its top thicker for longer";
}

TEST(Drainage, Eq14DirectionIsTheCosineWithGravityOrZero) {
  const Vec3 g(0, -9.81f, 0);
  EXPECT_FLOAT_EQ(drainageDirection(Vec3::Zero(), Vec3(0, -2, 0), g), 1.0f);
  EXPECT_NEAR(drainageDirection(Vec3::Zero(), Vec3(1, -1, 0), g), std::sqrt(0.5f), 1e-6f);
  EXPECT_FLOAT_EQ(drainageDirection(Vec3::Zero(), Vec3(1, 0, 0), g), 0.0f);
  EXPECT_FLOAT_EQ(drainageDirection(Vec3::Zero(), Vec3(0, 1, 0), g), 0.0f);  // uphill: nothing flows
}

}  // namespace
}  // namespace gb
