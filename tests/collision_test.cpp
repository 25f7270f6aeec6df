// Self-collision: film sheets pushed together repel and slip instead of passing through each other.
#include "collision.h"

#include <gtest/gtest.h>

#include "simulation.h"
#include "test_films.h"

namespace gb {
namespace {

double meanZ(const State& s, size_t from, size_t to) {
  double sum = 0;
  for (size_t i = from; i < to; ++i) sum += s.position.z[i];
  return sum / static_cast<double>(to - from);
}

Params twoSheetParams() {
  Params p;
  p.particlesAtFullSolution = 600;
  p.gravityY = 0.0f;
  return p;
}

TEST(Collision, ContactsAreSymmetricAcrossTheSheetsAndLeaveTheOneRingOut) {
  const Params p = twoSheetParams();
  Film film = test::makeTwoSheets(p, 0.015f, 0.0f);
  const size_t pairs = findContacts(p, 0.0f, 0.0f, film);
  EXPECT_GT(pairs, 100u);
  const size_t n = film.state.size(), half = n / 2;
  const std::vector<uint32_t>& c = film.topology.contacts;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t k = c[i]; k < c[i + 1]; ++k) {
      const uint32_t j = c[n + 1 + k];
      EXPECT_NE(i < half, j < half) << "contact " << i << "-" << j << " lies along one sheet";
      EXPECT_TRUE(std::binary_search(c.begin() + n + 1 + c[j], c.begin() + n + 1 + c[j + 1], i)) << "asymmetric";
    }
}

// The rest distance pair (i, j) had in a history, 0 when it was not listed there.
float restDistanceIn(const ContactHistory& history, uint32_t i, uint32_t j) {
  const std::vector<uint32_t>& c = history.contacts;
  const size_t n = history.particles;
  for (uint32_t k = n ? c[i] : 0; n && k < c[i + 1]; ++k)
    if (c[n + 1 + k] == j) return contactRestDistance(c, n, k);
  return 0.0f;
}

// Checks every listed pair's rest distance: the collision distance, or the largest separation since the pair was
// listed. Returns how many pairs rest farther apart than they are by more than `kept`.
size_t expectRestDistances(const Params& p, const Film& film, const ContactHistory& history, float kept) {
  const size_t n = film.state.size();
  const std::vector<uint32_t>& c = film.topology.contacts;
  EXPECT_EQ(c.size(), n + 1 + 2 * size_t{c[n]}) << "a rest distance for every partner entry";
  size_t farther = 0;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t k = c[i]; k < c[i + 1]; ++k) {
      const uint32_t j = c[n + 1 + k];
      const float separation = (film.state.position.get(i) - film.state.position.get(j)).norm();
      const float rest = contactRestDistance(c, n, k);
      EXPECT_EQ(rest, std::min(p.collisionDistance, std::max(restDistanceIn(history, i, j), separation)))
          << "pair " << i << "-" << j;
      farther += rest > separation + kept;
    }
  return farther;
}

void moveSecondSheet(Film& film, float dz) {
  for (size_t i = film.state.size() / 2; i < film.state.size(); ++i) film.state.position.z[i] += dz;
}

TEST(Collision, APairListedAlreadyCloseEntersAtItsSeparationAndKeepsTheLargestSinceThen) {
  const Params p = twoSheetParams();
  Film film = test::makeTwoSheets(p, 0.01f, 0.0f);  // 1 cm apart: inside the 2 cm collision distance
  ASSERT_GT(findContacts(p, 0.0f, 0.01f, film), 100u);
  // Entering already closer: at the pair's separation, so the new list holds no penalty energy.
  EXPECT_EQ(expectRestDistances(p, film, {}, 0.0f), 0u);
  ContactHistory history{film.topology.contacts, film.state.size()};

  moveSecondSheet(film, 0.005f);  // apart to 1.5 cm: the rest distances follow the separations out
  findContacts(p, 0.0f, 0.01f, film, history);
  EXPECT_EQ(expectRestDistances(p, film, history, 0.0f), 0u);
  history = {film.topology.contacts, film.state.size()};

  moveSecondSheet(film, -0.008f);  // together to 0.7 cm: pairs still listed keep what they had and push apart
  findContacts(p, 0.0f, 0.01f, film, history);
  EXPECT_GT(expectRestDistances(p, film, history, 0.007f), 100u) << "the pairs must keep their 1.5 cm";

  findContacts(p, 0.0f, 0.01f, film);  // no history (a new dip): from the present separations again
  EXPECT_EQ(expectRestDistances(p, film, {}, 0.0f), 0u);
}

TEST(Collision, TwoSheetsPushedTogetherDoNotPassThroughEachOther) {
  const Params p = twoSheetParams();
  for (bool collide : {true, false}) {
    Params q = p;
    if (!collide) q.collisionStiffness = 0.0f;  // the control: without contacts the sheets pass
    Film film = test::makeTwoSheets(q, 0.04f, 0.8f);
    const size_t half = film.state.size() / 2;
    Simulation sim(q, film, WandState{});
    double worstOrder = 1.0;
    for (int f = 0; f < 25; ++f) {  // 0.5 s: unobstructed, the first sheet would travel 0.2 m
      sim.advanceFrame(WandState{});
      const State& s = sim.film().state;
      worstOrder = std::min(worstOrder, meanZ(s, half, 2 * half) - meanZ(s, 0, half));
    }
    if (collide) {
      EXPECT_GT(worstOrder, 0.0) << "the moving sheet passed the other one";
    } else {
      EXPECT_LT(worstOrder, 0.0) << "the control must pass through, or the test shows nothing";
    }
  }
}

}  // namespace
}  // namespace gb

namespace gb {
namespace {

TEST(Collision, ImpactNumberIsTheFilmWeberNumber) {
  Params p;
  p.filmInertia = 0.1f;
  // 0.1 kg/m^2 x (5 m/s)^2 / 12.5 N/m = 0.2; receding or a film without tension: no impact.
  EXPECT_FLOAT_EQ(impactNumber(p, 5.0f, 12.5f), 0.2f);
  EXPECT_EQ(impactNumber(p, -5.0f, 12.5f), 0.0f);
  EXPECT_EQ(impactNumber(p, 5.0f, 0.0f), 0.0f);
}

// The approach speed at which two sheets' impact number reaches lambda_col.
float burstingSpeed(const Params& p, const Film& film) {
  return std::sqrt(p.collisionThreshold * film.state.elasticity[0] / p.filmInertia);
}

TEST(Collision, AHardImpactBurstsTheFilmAndAGentleOneDoesNot) {
  const Params p = twoSheetParams();
  const float vBurst = burstingSpeed(p, test::makeTwoSheets(p, 0.04f, 0.0f));
  for (float factor : {2.0f, 0.5f}) {
    Simulation sim(p, test::makeTwoSheets(p, 0.04f, factor * vBurst), WandState{});
    for (int f = 0; f < 3; ++f) sim.advanceFrame(WandState{});
    if (factor > 1) {
      EXPECT_GE(sim.burst().started, 0.0) << "a sheet thrown at " << factor * vBurst << " m/s must burst";
    } else {
      EXPECT_LT(sim.burst().started, 0.0) << "a sheet meeting another at " << factor * vBurst << " m/s must hold";
    }
  }
}

}  // namespace
}  // namespace gb

namespace gb {
namespace {

TEST(Collision, WindingNumberTellsInsideFromOutsideOfABubble) {
  const Film sphere = generateSphere(Params{}, Vec3(0, 1, 0), 0.5f, 2);
  // Exact up to the float positions of the icosphere: 1e-6.
  EXPECT_NEAR(windingNumber(sphere, Vec3(0, 1, 0)), 1.0, 1e-6);
  EXPECT_NEAR(windingNumber(sphere, Vec3(0.3f, 1.2f, 0.1f)), 1.0, 1e-6);
  EXPECT_NEAR(windingNumber(sphere, Vec3(2, 1, 0)), 0.0, 1e-6);
  EXPECT_NEAR(windingNumber(sphere, Vec3(0, 1.6f, 0)), 0.0, 1e-6);
}

}  // namespace
}  // namespace gb
