#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "capture/scripted_gestures.h"
#include "model/film.h"
#include "stages/stages.h"
#include "tests/mesh_checks.h"

namespace gb {
namespace {

Params smallFilm(float solution) {
  Params p;
  p.particlesAtFullSolution = 2000;
  p.solution = solution;
  return p;
}

WandState restingWands() { return gestureAt(Gesture::Straight, GestureOptions{}, 0.0); }

TEST(FilmGeneration, ParticleCountFollowsTheRemainingSolution) {
  for (ToolKind kind : {ToolKind::TwoWands, ToolKind::Ring}) {
    WandTool tool;
    tool.kind = kind;
    const size_t full = generateFilm(smallFilm(1.0f), tool, restingWands()).state.size();
    const size_t threeQuarters = generateFilm(smallFilm(0.75f), tool, restingWands()).state.size();
    const size_t half = generateFilm(smallFilm(0.5f), tool, restingWands()).state.size();
    // Exactly round(solution x particlesAtFullSolution): the ratios 1 : 0.75 : 0.5 up to rounding.
    EXPECT_EQ(full, 2000u);
    EXPECT_EQ(threeQuarters, 1500u);
    EXPECT_EQ(half, 1000u);
  }
}

TEST(FilmGeneration, LessSolutionGivesASmallerRounderTwoWandFilm) {
  auto extent = [](const Film& f) {
    Eigen::Vector3f lo = f.state.position.get(0), hi = lo;
    for (size_t i = 0; i < f.state.size(); ++i) {
      lo = lo.cwiseMin(f.state.position.get(i));
      hi = hi.cwiseMax(f.state.position.get(i));
    }
    return Eigen::Vector3f(hi - lo);
  };
  const Film full = generateFilm(smallFilm(1.0f), WandTool{}, restingWands());
  const Film half = generateFilm(smallFilm(0.5f), WandTool{}, restingWands());
  const Eigen::Vector3f a = extent(full), b = extent(half);
  EXPECT_LT(b.y(), a.y());  // hangs less deep
  // Height over half width: 0.8 / 0.5 at full solution, 0.4 / 0.5 = nearly a half disc at half.
  const float aspectFull = a.y() / (0.5f * a.x()), aspectHalf = b.y() / (0.5f * b.x());
  EXPECT_LT(std::abs(aspectHalf - 1.0f), std::abs(aspectFull - 1.0f));
}

TEST(FilmGeneration, MeshIsAnOrientedManifoldDiscOnTheFrame) {
  const Params p = smallFilm(1.0f);
  for (ToolKind kind : {ToolKind::TwoWands, ToolKind::Ring}) {
    WandTool tool;
    tool.kind = kind;
    const Film film = generateFilm(p, tool, restingWands());
    const Topology& topo = film.topology;
    EXPECT_EQ(test::eulerCharacteristic(topo), 1);  // a disc
    test::expectAdjacencyMatchesTriangles(topo);
    const WireFrame frame = makeWireFrame(tool, restingWands(), film.stringLength, Vec3(0, -9.81f, 0));
    const Vec3 frameNormal = frame.axis.cross(frame.down);
    size_t boundary = 0;
    for (size_t i = 0; i < film.state.size(); ++i) {
      // All triangles face the same way, so every vertex normal is the frame's normal.
      EXPECT_NEAR(film.state.normal.get(i).dot(frameNormal), 1.0f, 1e-4f) << "particle " << i;
      // Thickness starts at e0 = w_e x 100 um everywhere.
      EXPECT_NEAR(film.state.thickness[i], initialThickness(p), 1e-3f * initialThickness(p));
      if (!topo.boundary[i]) continue;
      ++boundary;
      EXPECT_NEAR((film.state.position.get(i) - wirePoint(frame, film.state.wireParam[i])).norm(), 0.0f, 1e-5f);
    }
    EXPECT_GT(boundary, 50u);
  }
}

TEST(FilmGeneration, SpringsRestAtTheirPrestrainedInitialLengths) {
  const Params p = smallFilm(1.0f);
  const Film film = generateFilm(p, WandTool{}, restingWands());
  const Topology& topo = film.topology;
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const float d =
        (film.state.position.get(topo.springEnds[2 * k]) - film.state.position.get(topo.springEnds[2 * k + 1])).norm();
    EXPECT_FLOAT_EQ(d * (1.0f - p.springPrestrain), topo.restLength[k]);
  }
  // Triangles are well shaped: no edge is more than three times the median one.
  std::vector<float> lengths = topo.restLength;
  std::sort(lengths.begin(), lengths.end());
  EXPECT_LT(lengths.back(), 3.0f * lengths[lengths.size() / 2]);
}

TEST(FilmGeneration, SphereIsClosedOutwardAndHasTheRightVolume) {
  const Params p;
  const Film sphere = generateSphere(p, Vec3(0, 1, 0), 0.5f, 3);
  EXPECT_TRUE(sphere.topology.isClosed());
  EXPECT_EQ(test::eulerCharacteristic(sphere.topology), 2);
  test::expectAdjacencyMatchesTriangles(sphere.topology);
  double volume = 0;
  for (size_t t = 0; t < sphere.topology.triangleCount(); ++t)
    volume += triangleVolume(sphere.topology, sphere.state, t, Vec3(0, 1, 0));
  // An icosphere with 3 subdivisions is inscribed: its volume is 1.5% under the sphere's.
  const double exact = 4.0 / 3.0 * std::numbers::pi * 0.125;
  EXPECT_NEAR(volume / exact, 0.985, 0.01);
  for (size_t i = 0; i < sphere.state.size(); ++i)
    EXPECT_GT(sphere.state.normal.get(i).dot(sphere.state.position.get(i) - Vec3(0, 1, 0)), 0.0f);
}

TEST(FilmGeneration, RejectsInvalidParameters) {
  Params p;
  p.solution = 0.0f;
  EXPECT_THROW(generateFilm(p, WandTool{}, restingWands()), std::invalid_argument);
  WandState together;  // both tips at the origin: the loop encloses nothing
  EXPECT_THROW(generateFilm(Params{}, WandTool{}, together), std::invalid_argument);
}

}  // namespace
}  // namespace gb
