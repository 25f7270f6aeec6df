#include "topology/body_touch.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "model/film.h"
#include "simulation/simulation.h"

namespace gb {
namespace {

// A flat patch of body points (a palm, a chest) in the plane z = z0, spaced `step` apart, centred at (cx, cy).
std::vector<Vec3> patch(float cx, float cy, float z0, float half, float step) {
  std::vector<Vec3> points;
  for (float x = -half; x <= half + 1e-6f; x += step)
    for (float y = -half; y <= half + 1e-6f; y += step) points.emplace_back(cx + x, cy + y, z0);
  return points;
}

constexpr bool kOnTheWire = true, kFree = false;  // touches()'s film: on the wands' wire, or a free bubble

// A free bubble of radius 0.3 m at (0, 1.5, 0): its front pole at z = 0.3.
Film bubble() {
  Params params;
  return generateSphere(params, Vec3(0.0f, 1.5f, 0.0f), 0.3f, 3);
}

TEST(BodyTouch, TheGridFindsTheNearestPointAScanFinds) {
  // Exactness of the grid against a linear scan, on a cloud as uneven as a depth image's (dense near, sparse far).
  std::mt19937 random(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Vec3> points;
  for (int p = 0; p < 3000; ++p) points.emplace_back(u(random), 1.0f + u(random), 2.0f + 0.2f * u(random));
  const float reach = 0.05f;
  const BodyGrid grid(points, 0.02f);  // cells smaller than the reach: the shells search beyond the first
  int found = 0;
  for (int q = 0; q < 2000; ++q) {
    const Vec3 x(1.1f * u(random), 1.0f + 1.1f * u(random), 2.0f + 0.3f * u(random));
    float best = std::numeric_limits<float>::infinity();
    for (const Vec3& p : points) best = std::min(best, (p - x).norm());
    const std::optional<float> near = grid.nearestWithin(x, reach);
    ASSERT_EQ(near.has_value(), best <= reach) << "query " << q;
    if (near) {
      EXPECT_FLOAT_EQ(*near, best);
      ++found;
    }
  }
  EXPECT_GT(found, 50) << "the queries must also test points that are found";
}

TEST(BodyTouch, APalmAtTheFilmTouchesItAndOneAtTheGripOnlyWhenTheBubbleIsFree) {
  const Film film = bubble();
  std::vector<uint8_t> armed(film.state.size(), 1);  // every particle has been clear of the body
  BodyTouch touch;
  // A palm 1 cm in front of the bubble's front pole (z = 0.3): within the 2 cm touch distance of the pole.
  BodyPoints body{patch(0.0f, 1.5f, 0.31f, 0.05f, 0.005f), {}, 0.0};
  touch.setBody(body);
  const std::vector<Touch> touching = touch.touches(film.state, armed, kOnTheWire);
  ASSERT_FALSE(touching.empty()) << "a palm 1 cm from the film touches it";
  for (const Touch& t : touching) EXPECT_GT(t.position.z(), 0.25f) << "only the front pole touches";
  ASSERT_TRUE(touch.burstingTouch(touching)) << "dry skin bursts a film at any speed";
  // The same palm holding a wand (a grip 5 cm from it, within the 30 cm grip radius): the film on the wire there is
  // the hand's own; a free bubble is not.
  body.grips = {Vec3(0.0f, 1.5f, 0.36f)};
  touch.setBody(body);
  EXPECT_TRUE(touch.touches(film.state, armed, kOnTheWire).empty())
      << "the hand on the wand does not burst its own film";
  EXPECT_FALSE(touch.touches(film.state, armed, kFree).empty()) << "a hand bursts a free bubble";
  // A palm 5 cm away: no touch.
  touch.setBody({patch(0.0f, 1.5f, 0.35f, 0.05f, 0.005f), {}, 0.1});
  EXPECT_TRUE(touch.touches(film.state, armed, kOnTheWire).empty());
}

TEST(BodyTouch, ATouchsApproachSpeedIsTheBodysClosingOverItsLastFrame) {
  // The palm comes 6 cm nearer over a 1/30 s frame: 1.8 m/s, the particle at rest. Within 0.3 m/s: the body's frame
  // before is measured at the particle's position to the nearest point, and the front pole's particle sits within
  // a few millimetres of the palm's axis.
  const Film film = bubble();
  std::vector<uint8_t> armed(film.state.size(), 1);
  BodyTouch touch;
  touch.setBody({patch(0.0f, 1.5f, 0.37f, 0.05f, 0.005f), {}, 0.0});
  touch.setBody({patch(0.0f, 1.5f, 0.31f, 0.05f, 0.005f), {}, 1.0 / 30.0});
  const std::vector<Touch> touching = touch.touches(film.state, armed, kOnTheWire);
  ASSERT_FALSE(touching.empty());
  EXPECT_NEAR(touching.front().approachSpeed, 1.8f, 0.3f);
}

TEST(BodyTouch, WetHandsPushTheFilmAndOnlyAStrikeBurstsIt) {
  Film film = bubble();
  std::vector<uint8_t> armed(film.state.size(), 1);
  TouchOptions wet;
  wet.wetHands = true;
  BodyTouch touch(wet);
  // A slow palm (3 cm in a 1/30 s frame: 0.9 m/s, under the 1.5 m/s strike speed) 5 mm into the film.
  touch.setBody({patch(0.0f, 1.5f, 0.325f, 0.08f, 0.005f), {}, 0.0});
  touch.setBody({patch(0.0f, 1.5f, 0.295f, 0.08f, 0.005f), {}, 1.0 / 30.0});
  std::vector<Touch> touching = touch.touches(film.state, armed, kOnTheWire);
  ASSERT_FALSE(touching.empty());
  EXPECT_FALSE(touch.burstingTouch(touching)) << "a wet hand passes through a film at 0.9 m/s";
  EXPECT_GT(touch.push(film.state, touching), 0u);
  // Pushed out: no particle is left nearer the palm than the touch distance (less 1 mm of float rounding).
  const BodyGrid palm(patch(0.0f, 1.5f, 0.295f, 0.08f, 0.005f), wet.distance);
  for (size_t i = 0; i < film.state.size(); ++i)
    EXPECT_FALSE(palm.nearestWithin(film.state.position.get(i), wet.distance - 1e-3f))
        << "particle " << i << " still in the palm";
  // A strike: 15 cm in a frame (4.5 m/s).
  Film struck = bubble();
  touch.setBody({patch(0.0f, 1.5f, 0.445f, 0.08f, 0.005f), {}, 2.0 / 30.0});
  touch.setBody({patch(0.0f, 1.5f, 0.295f, 0.08f, 0.005f), {}, 3.0 / 30.0});
  touching = touch.touches(struck.state, armed, kOnTheWire);
  const std::optional<Touch> burst = touch.burstingTouch(touching);
  ASSERT_TRUE(burst) << "a strike faster than the strike speed bursts even a wet film";
  EXPECT_GT(burst->approachSpeed, wet.strikeSpeed);
}

TEST(BodyTouch, AFilmMadeInsideTheBodyTouchesItOnlyOnceDrawnClear) {
  // Hands held at the sides make the film across the hips: it passes through the body until it has been clear of it.
  const Film film = bubble();
  std::vector<uint8_t> armed;  // a new film: none armed
  BodyTouch touch;
  touch.setBody({patch(0.0f, 1.5f, 0.31f, 0.05f, 0.005f), {}, 0.0});
  EXPECT_TRUE(touch.touches(film.state, armed, kOnTheWire).empty()) << "the pole made inside the palm is not yet armed";
  EXPECT_EQ(armed.size(), film.state.size());
  touch.setBody({patch(0.0f, 1.5f, 0.36f, 0.05f, 0.005f), {}, 0.1});  // 5 cm clear: not yet the 10 cm to arm
  EXPECT_TRUE(touch.touches(film.state, armed, kOnTheWire).empty());
  touch.setBody({patch(0.0f, 1.5f, 0.31f, 0.05f, 0.005f), {}, 0.15});
  EXPECT_TRUE(touch.touches(film.state, armed, kOnTheWire).empty())
      << "jitter within the arming distance does not arm it";
  touch.setBody({patch(0.0f, 1.5f, 0.42f, 0.05f, 0.005f), {}, 0.1});  // drawn clear: every particle armed
  EXPECT_TRUE(touch.touches(film.state, armed, kOnTheWire).empty());
  touch.setBody({patch(0.0f, 1.5f, 0.31f, 0.05f, 0.005f), {}, 0.2});  // and back: now it touches
  EXPECT_FALSE(touch.touches(film.state, armed, kOnTheWire).empty());
}

// A free bubble in a simulation, the wands far below it.
std::unique_ptr<Simulation> freeBubble(float lift) {
  Params params;
  params.bubbleLift = lift;
  WandState wands;
  wands.leftPosition = Vec3(-0.5f, 0.2f, 0.0f);
  wands.rightPosition = Vec3(0.5f, 0.2f, 0.0f);
  return std::make_unique<Simulation>(params, bubble(), wands);
}

TEST(BodyTouch, ABubbleWhoseAirCarriesItsWeightFloatsStill) {
  // A second: gravity pulls on the film's liquid while the film's inertia (filmInertia) is far larger, so a bubble
  // whose air carries nothing sinks slowly (17 cm), and one whose air carries its weight not at all. 2 cm allows for
  // the bubble rounding up as its slack springs contract.
  for (const float lift : {0.0f, 1.0f}) {
    auto sim = freeBubble(lift);
    const Vec3 start = centroid(sim->film().state);
    WandState wands;
    wands.leftPosition = Vec3(-0.5f, 0.2f, 0.0f);
    wands.rightPosition = Vec3(0.5f, 0.2f, 0.0f);
    for (int frame = 0; frame < 50; ++frame) sim->advanceFrame(wands);
    const float drop = start.y() - centroid(sim->film().state).y();
    std::printf("bubbleLift %.0f: the bubble sank %.4f m in 1 s\n", lift, drop);
    if (lift > 0.0f)
      EXPECT_LT(std::abs(drop), 0.02f) << "a neutrally buoyant bubble stays where it was placed";
    else
      EXPECT_GT(drop, 0.1f) << "a bubble whose air carries nothing falls";
  }
}

TEST(BodyTouch, ATouchBurstsAFreeBubbleWhereItTouched) {
  auto sim = freeBubble(1.0f);
  WandState wands;
  wands.leftPosition = Vec3(-0.5f, 0.2f, 0.0f);
  wands.rightPosition = Vec3(0.5f, 0.2f, 0.0f);
  // The palm first 30 cm away (the bubble is clear of the body: armed), then 1 cm in front of the front pole, in the
  // frame before that 6 cm farther: it struck at 1.8 m/s. Its grip (the hand holds a wand) does not matter: the bubble
  // is free.
  sim->setBody({patch(0.0f, 1.5f, 0.6f, 0.05f, 0.005f), {Vec3(0.0f, 1.5f, 0.63f)}, 0.0});
  sim->advanceFrame(wands);
  ASSERT_FALSE(sim->lastEvents().started);
  sim->setBody({patch(0.0f, 1.5f, 0.37f, 0.05f, 0.005f), {Vec3(0.0f, 1.5f, 0.4f)}, 1.0 / 30.0});
  sim->setBody({patch(0.0f, 1.5f, 0.31f, 0.05f, 0.005f), {Vec3(0.0f, 1.5f, 0.34f)}, 2.0 / 30.0});
  sim->advanceFrame(wands);
  ASSERT_TRUE(sim->lastEvents().started);
  EXPECT_STREQ(sim->lastEvents().cause, "touch");
  ASSERT_TRUE(sim->lastTouch());
  EXPECT_GT(sim->lastTouch()->position.z(), 0.27f) << "the crack starts at the front pole, where the palm is";
}

TEST(BodyTouch, WetHandsPassThroughAFreeBubbleWithoutBurstingIt) {
  Params params;
  params.bubbleLift = 1.0f;
  params.wetHands = 1;
  WandState wands;
  wands.leftPosition = Vec3(-0.5f, 0.2f, 0.0f);
  wands.rightPosition = Vec3(0.5f, 0.2f, 0.0f);
  Simulation sim(params, bubble(), wands);
  // The palm 30 cm away (the bubble armed), then pressed slowly 2 cm into the front pole (0.6 m/s over the frame,
  // under the 1.5 m/s strike speed).
  sim.setBody({patch(0.0f, 1.5f, 0.6f, 0.05f, 0.005f), {}, 0.0});
  sim.advanceFrame(wands);
  sim.setBody({patch(0.0f, 1.5f, 0.30f, 0.05f, 0.005f), {}, 1.0 / 30.0});
  sim.setBody({patch(0.0f, 1.5f, 0.28f, 0.05f, 0.005f), {}, 2.0 / 30.0});
  sim.advanceFrame(wands);
  EXPECT_FALSE(sim.lastEvents().started) << "a wet hand pushes the film";
  EXPECT_FALSE(sim.lastTouch());
}

TEST(BodyTouch, AFarFlungCloudCostsNoMoreThanTheGridsCap) {
  // Two points 100 m apart with a 2 cm reach would need 10^16 cells: the cells grow instead, the query stays exact.
  const BodyGrid grid({Vec3(0, 0, 0), Vec3(100, 100, 100)}, 0.02f);
  EXPECT_TRUE(grid.nearestWithin(Vec3(0.01f, 0, 0), 0.02f));
  EXPECT_FALSE(grid.nearestWithin(Vec3(0.05f, 0, 0), 0.02f));
  EXPECT_TRUE(grid.nearestWithin(Vec3(100, 100, 99.99f), 0.02f));
}

}  // namespace
}  // namespace gb
