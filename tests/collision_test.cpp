// Self-collision: film sheets pushed together repel and slip instead of passing through each other.
#include "topology/collision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "scene/scene_file.h"
#include "simulation/simulation.h"
#include "stages/cpu_stepper.h"
#include "tests/test_films.h"

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

// Every pair findContacts must list, by testing every pair against its rule (collision.h): living film particles
// that are not one-ring neighbours, closer than the collision distance plus the pair's margin, across the film.
std::vector<std::vector<uint32_t>> contactsByTestingEveryPair(const Params& p, float frameTime, float slack,
                                                              const Film& film) {
  const State& s = film.state;
  const Topology& topo = film.topology;
  const size_t n = s.size();
  auto inFilm = [&](size_t i) { return s.alive[i] && topo.triangleOffset[i + 1] > topo.triangleOffset[i]; };
  std::vector<std::vector<uint32_t>> partners(n);
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = i + 1; j < n; ++j) {
      if (!inFilm(i) || !inFilm(j)) continue;
      const Vec3 d = s.position.get(j) - s.position.get(i);
      const float closing = (s.velocity.get(i) - s.velocity.get(j)).norm();
      const float reach = p.collisionDistance + std::min(kMaxContactMargin, frameTime * closing + slack);
      const float length = d.squaredNorm();
      if (!(length > 0 && length < reach * reach)) continue;
      const float alongI = s.normal.get(i).dot(d), alongJ = s.normal.get(j).dot(d);
      if (!(alongI * alongI > 0.5f * length || alongJ * alongJ > 0.5f * length)) continue;
      const auto ring = topo.springNeighbour.begin();
      if (std::find(ring + topo.springOffset[i], ring + topo.springOffset[i + 1], j) != ring + topo.springOffset[i + 1])
        continue;
      partners[i].push_back(j);
      partners[j].push_back(i);
    }
  for (auto& list : partners) std::sort(list.begin(), list.end());
  return partners;
}

// findContacts' lists against testing every pair; returns the number of pairs.
size_t expectTheSearchListsEveryPair(const Params& p, Film& film, const char* name) {
  const size_t pairs = findContacts(p, p.frameTime, 0.005f, film);
  const auto expected = contactsByTestingEveryPair(p, p.frameTime, 0.005f, film);
  const size_t n = film.state.size();
  const std::vector<uint32_t>& listed = film.topology.contacts;
  size_t expectedPairs = 0;
  for (uint32_t i = 0; i < n; ++i) {
    expectedPairs += expected[i].size();
    const std::vector<uint32_t> found(listed.begin() + n + 1 + listed[i], listed.begin() + n + 1 + listed[i + 1]);
    EXPECT_EQ(found, expected[i]) << name << ": the partners of particle " << i;
    if (found != expected[i]) break;
  }
  EXPECT_EQ(2 * pairs, expectedPairs) << name;
  std::printf("%s: %zu particles, %zu pairs\n", name, n, pairs);
  return pairs;
}

TEST(Collision, TheSearchListsExactlyThePairsThatTestingEveryPairFinds) {
  // The search reads each bucket only within the radius it proves holds every partner (partnerRadius), and skips
  // the buckets beyond it, and each particle searches only within its own reach: its lists must be exactly those of
  // testing every pair, on sheets that meet (one of them moving, the other still), on sheets sharing their cells, on
  // a fold, and on the default performance's film as it is drawn, after it pinched off into a crumpled free bubble
  // (tens of thousands of pairs), and as a smooth bubble in flight, whose cells are three particle spacings wide,
  // wider than its reach (collision.cpp cellSizeFor).
  const Params sheets = twoSheetParams();
  Film apart = test::makeTwoSheets(sheets, 0.022f, 0.8f);
  EXPECT_GT(expectTheSearchListsEveryPair(sheets, apart, "two sheets 2.2 cm apart, one moving"), 100u);
  // Within a nearly flat cell a partner can only lie within the partner radius H / (sqrt(1/2) - tilt) (collision.cpp
  // partnerRadius): sheets 1 mm apart share their cells (H = 1 mm), and the second, shifted by 0.98 mm, puts each
  // particle's partner 1.40 mm away, inside the 1.414 mm that 45 degrees allows and at 98% of the 1.43 mm radius the
  // search reads; a radius without the 1 / sqrt(1/2) would lose every pair. Once along the axes, once turned so
  // that the cells cut the sheets obliquely.
  for (float angle : {0.0f, 0.7f}) {
    Film close = test::shiftedSheets(sheets, 0.001f, 0.00098f, angle);
    EXPECT_GT(expectTheSearchListsEveryPair(sheets, close, "sheets 1 mm apart, shifted 0.98 mm"), 500u);
  }
  Film folded = test::foldedFilm(Params{}, 170.0f * 3.14159265f / 180.0f, 1);
  EXPECT_GT(expectTheSearchListsEveryPair(Params{}, folded, "the default film folded"), 1000u);

  const Scene scene = resolveScene("default");
  const Params& params = scene.run.params;
  const GestureOptions& stroke = scene.run.gestureOptions;
  Simulation sim(params, WandTool{}, gestureAt(Gesture::Giant, stroke, 0.0));
  const std::map<int, size_t> fewestPairsAtFrame{{80, 1000}, {110, 1000}, {200, 100}};
  for (int f = 1; f <= 200; ++f) {
    sim.advanceFrame(gestureAt(Gesture::Giant, stroke, static_cast<double>(f) * params.frameTime));
    if (!fewestPairsAtFrame.contains(f)) continue;
    Film film = sim.film();
    const std::string name = "the default performance at frame " + std::to_string(f);
    EXPECT_GT(expectTheSearchListsEveryPair(params, film, name.c_str()), fewestPairsAtFrame.at(f));
  }
}

TEST(Collision, AReusedSearchListsWhatAFreshSearchLists) {
  // The simulation's search keeps its cell table and lists from one frame to the next (ContactSearch): nothing a
  // larger film with many pairs left in them may show in a smaller film's lists, nor the other way round. Exactly
  // the same lists, pair for pair and rest distance for rest distance.
  const Params sheets = twoSheetParams(), film = Params{};
  Film folded = test::foldedFilm(film, 170.0f * 3.14159265f / 180.0f, 1);
  Film close = test::shiftedSheets(sheets, 0.001f, 0.00098f, 0.7f);
  ContactSearch search;
  for (int round = 0; round < 2; ++round)
    for (auto [params, original] : {std::pair{&film, &folded}, std::pair{&sheets, &close}}) {
      Film fresh = *original, reused = *original;
      const size_t pairs = findContacts(*params, params->frameTime, 0.005f, fresh);
      EXPECT_GT(pairs, 500u);
      EXPECT_EQ(search.find(*params, params->frameTime, 0.005f, reused), pairs) << "round " << round;
      EXPECT_EQ(reused.topology.contacts, fresh.topology.contacts)
          << "round " << round << ", " << original->state.size() << " particles";
    }
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
  // Exact: inside (within its box), outside within its box (a corner), outside the box.
  EXPECT_TRUE(insideClosedFilm(sphere, Vec3(0.3f, 1.2f, 0.1f)));
  EXPECT_FALSE(insideClosedFilm(sphere, Vec3(0.45f, 1.45f, 0.0f)));
  EXPECT_FALSE(insideClosedFilm(sphere, Vec3(2, 1, 0)));
}

}  // namespace
}  // namespace gb
