// Every formula of the step against a value computed by hand.
#include "stages/stages.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "solver/energy_budget.h"
#include "tests/test_films.h"

namespace gb {
namespace {

// Float32 evaluation of a short formula: a few ulps of the result.
constexpr float kFormulaTolerance = 1e-6f;

TEST(Elasticity, MarangoniWhileYoungGibbsAfterEq4) {
  Params p;
  p.elasticityWeight = 12.5f;
  p.elasticityThickness = 4e-6f;
  p.marangoniLifetime = 0.2f;
  // e = k: x = 1. Marangoni 2 w_E x / (x + 2) = 25 / 3; Gibbs 4 w_E x / (x + 2)^2 = 50 / 9.
  EXPECT_NEAR(elasticityOf(p, 4e-6f, 0.1f), 25.0f / 3.0f, 1e-5f);
  EXPECT_NEAR(elasticityOf(p, 4e-6f, 0.3f), 50.0f / 9.0f, 1e-5f);
  // e = 2k: the Gibbs peak w_E / 2; thicker films are softer (inversely proportional to thickness).
  EXPECT_NEAR(elasticityOf(p, 8e-6f, 1.0f), 6.25f, 1e-5f);
  EXPECT_LT(elasticityOf(p, 40e-6f, 1.0f), elasticityOf(p, 8e-6f, 1.0f));
}

TEST(Elasticity, GibbsHoldsBelowItsFloorAndTheMarangoniBranchDoesNot) {
  Params p;
  p.elasticityWeight = 12.5f;
  p.elasticityThickness = 4e-6f;
  p.marangoniLifetime = 0.2f;
  p.gibbsFloorThickness = 1.5e-6f;
  // x = 0.375 at the floor: 4 w_E x / (x + 2)^2 = 18.75 / 5.640625. Film thinner than the floor keeps it exactly
  // (the same float formula at the same x); above the floor Eq. (4) is untouched.
  const float atFloor = 12.5f * 4.0f * 0.375f / (2.375f * 2.375f);
  EXPECT_NEAR(elasticityOf(p, 1.5e-6f, 1.0f), atFloor, 1e-5f);
  EXPECT_EQ(elasticityOf(p, 0.3e-6f, 1.0f), elasticityOf(p, 1.5e-6f, 1.0f));
  EXPECT_EQ(elasticityOf(p, 20e-9f, 1.0f), elasticityOf(p, 1.5e-6f, 1.0f));
  EXPECT_NEAR(elasticityOf(p, 4e-6f, 1.0f), 50.0f / 9.0f, 1e-5f);
  // Young film follows Marangoni's branch all the way down; a floor of 0 is the paper's formula.
  EXPECT_LT(elasticityOf(p, 0.3e-6f, 0.1f), elasticityOf(p, 1.5e-6f, 0.1f));
  p.gibbsFloorThickness = 0.0f;
  EXPECT_NEAR(elasticityOf(p, 0.4e-6f, 1.0f), 12.5f * 4.0f * 0.1f / (2.1f * 2.1f), 1e-5f);
}

TEST(FilmState, ThicknessIsLiquidOverVoronoiArea) {
  const Params p;
  Film film = test::makeHexagon(p);
  State& s = film.state;
  s.liquid[0] = 3e-10f;
  s.voronoiArea[0] = 1.5e-4f;
  s.lifetime[0] = 0.5f;
  filmState(p, 0.01f, s, 0);
  EXPECT_NEAR(s.thickness[0], 2e-6f, 2e-6f * kFormulaTolerance);
  EXPECT_FLOAT_EQ(s.elasticity[0], elasticityOf(p, s.thickness[0], 0.5f));
  EXPECT_FLOAT_EQ(s.lifetime[0], 0.51f);
}

TEST(Geometry, MixedVoronoiAreaOfTheRegularHexagonCentre) {
  // Six equilateral triangles of side 1: the centre's Voronoi region is a hexagon of inradius 1/2,
  // area 6 * (1/2)^2 / sqrt(3) = sqrt(3)/2.
  const Params p;
  Film film = test::makeHexagon(p);
  computeGeometry(film.topology, film.state);
  EXPECT_NEAR(film.state.voronoiArea[0], std::sqrt(3.0f) / 2.0f, kFormulaTolerance);
  EXPECT_NEAR(film.state.normal.get(0).z(), 1.0f, kFormulaTolerance);
}

TEST(Geometry, MixedVoronoiAreasTileRightAndObtuseTriangles) {
  const Params p;
  // Right isosceles triangle, legs 1: the right-angle corner gets 1/4, the others 1/8 each (circumcentre
  // on the hypotenuse).
  Film right = test::makeFilm(p, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  computeGeometry(right.topology, right.state);
  EXPECT_NEAR(right.state.voronoiArea[0], 0.25f, kFormulaTolerance);
  EXPECT_NEAR(right.state.voronoiArea[1], 0.125f, kFormulaTolerance);
  EXPECT_NEAR(right.state.voronoiArea[2], 0.125f, kFormulaTolerance);
  // Obtuse at particle 0: it gets half the area 0.5, the others a quarter each.
  Film obtuse = test::makeFilm(p, {{0, 0, 0}, {1, 0.2f, 0}, {-1, 0.2f, 0}}, {0, 1, 2});
  computeGeometry(obtuse.topology, obtuse.state);
  const float area = 0.2f;  // base 2, height 0.2
  EXPECT_NEAR(obtuse.state.voronoiArea[0], area / 2, kFormulaTolerance);
  EXPECT_NEAR(obtuse.state.voronoiArea[1], area / 4, kFormulaTolerance);
  EXPECT_NEAR(obtuse.state.voronoiArea[2], area / 4, kFormulaTolerance);
}

TEST(Geometry, FourTrianglesAtATimeAreTheSameFloatsAsOneAtATime) {
  // triangleGeometries and triangleVolumes take four triangles in the SSE lanes: each lane must give exactly what
  // triangleGeometry, triangleVolume and triangleVolumeAtStart give, in every case of the mixed Voronoi area (acute,
  // obtuse at any corner, collapsed), on a film jittered by up to 60% of its springs in every direction.
  const Params p;
  Film film = test::makeFreeDisc(p);
  State& s = film.state;
  const Topology& topo = film.topology;
  test::jitterWithWireParticles(film, 0.6f, 7);  // the wire's particles at the step's start where it put them: now
  const uint32_t* collapsed = &topo.triangles[3 * 9];
  s.position.set(collapsed[1], s.position.get(collapsed[0]));  // a triangle of no area
  fitTriangleArrays(topo, s);
  const size_t triangles = topo.triangleCount();
  ASSERT_NE(triangles % 4, 0u);  // the tail after the last four is done one at a time
  State lanes = s;
  triangleGeometries(topo, lanes, 0, triangles);
  std::vector<float> volumes(triangles), startVolumes(triangles);
  const Vec3 origin(0.1f, 1.2f, -0.3f);
  triangleVolumes(topo, s, origin, false, 0, triangles, volumes.data());
  triangleVolumes(topo, s, origin, true, 0, triangles, startVolumes.data());
  int obtuse = 0;
  for (size_t t = 0; t < triangles; ++t) {
    triangleGeometry(topo, s, t);
    EXPECT_EQ(lanes.triangleNormal.get(t), s.triangleNormal.get(t)) << "triangle " << t;
    for (size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(lanes.cornerArea[3 * t + c], s.cornerArea[3 * t + c]) << "triangle " << t << ", corner " << c;
      const float area = 0.5f * s.triangleNormal.get(t).norm();
      obtuse += area > 0 && s.cornerArea[3 * t + c] == 0.5f * area;
    }
    EXPECT_EQ(volumes[t], triangleVolume(topo, s, t, origin)) << "triangle " << t;
    EXPECT_EQ(startVolumes[t], triangleVolumeAtStart(topo, s, t, origin)) << "triangle " << t;
  }
  EXPECT_GT(obtuse, 100);                // the jitter made many obtuse triangles
  EXPECT_EQ(s.cornerArea[3 * 9], 0.0f);  // the collapsed one shares its zero area
}

TEST(AirInflow, Eq5FallsOffWithDistanceAndOpposesTheWands) {
  Params p;
  StepUniforms u;
  WandState wands;
  wands.leftPosition = Vec3(-1, 0, 0);
  wands.rightPosition = Vec3(3, 0, 0);
  wands.leftVelocity = wands.rightVelocity = Vec3(0, 0, 1);
  setWands(u, wands);
  u.airVolume = 0.5f;
  u.wandAlignment = 1.0f;
  // At the origin: distances 1 and 3, so -0.5 * (1/2 + 1/4) along z.
  const Vec3 air = airInflowAt(p, u, Vec3::Zero());
  EXPECT_NEAR(air.z(), -0.375f, kFormulaTolerance);
  EXPECT_NEAR(air.x(), 0.0f, kFormulaTolerance);
  // The single ring wand blows with its right hand only.
  u.leftInflowWeight = 0.0f;
  EXPECT_NEAR(airInflowAt(p, u, Vec3::Zero()).z(), -0.125f, kFormulaTolerance);
}

TEST(AirTransfer, Eq7And8WeightedMeanOfNeighboursPointingIn) {
  Params p;
  p.airDirectionThreshold = 0.6f;
  Film film = test::makeHexagon(p);
  State& s = film.state;
  // Neighbour 4 sits at (-1, 0, 0); its air points along +x, straight at the centre: a_dir = 1.
  // Neighbour 3 at (-1/2, sqrt3/2, 0) has air along +x too: a_dir = cos 60 deg = 0.5 < 0.6, so it is ignored.
  // Neighbour 5 at (-1/2, -sqrt3/2, 0) blows twice as hard, 12 degrees off the centre: a_dir = 0.975.
  s.airFlow.set(4, Vec3(1, 0, 0));
  s.airFlow.set(3, Vec3(1, 0, 0));
  const Vec3 toCentre = -s.position.get(5);
  const Vec3 air5 = 2.0f * (toCentre + Vec3(0.3f, 0, 0)).normalized();
  s.airFlow.set(5, air5);
  const float aDir5 = toCentre.normalized().dot(air5.normalized());
  ASSERT_GT(aDir5, 0.6f);
  film.topology.boundary[0] = 0;
  airTransfer(p, film.topology, s, 0);
  const Vec3 expected = (1.0f * Vec3(1, 0, 0) + aDir5 * air5) / (1.0f + aDir5);
  EXPECT_NEAR((s.airFlowNext.get(0) - expected).norm(), 0.0f, kFormulaTolerance);
  // A boundary ("end") particle takes the fresh inflow instead (Algorithm 2, line 2).
  s.airInflow.set(1, Vec3(0, 0, -3));
  airTransfer(p, film.topology, s, 1);
  EXPECT_EQ(s.airFlowNext.get(1), Vec3(0, 0, -3));
}

TEST(Forces, Eq3SpringWithMeanElasticityAndProjectedDamping) {
  Params p;
  p.gravityY = 0.0f;
  p.airDrag = 0.0f;
  p.airPressureGain = 0.0f;
  p.springDamping = 0.5f;
  p.springPrestrain = 0.0f;  // rest lengths are the creation distances
  // One triangle; stretch the spring 0-1 by 0.1 along x and give particle 1 a velocity.
  Film film = test::makeFilm(p, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  State& s = film.state;
  s.position.set(1, Vec3(1.1f, 0, 0));
  s.elasticity[0] = 2.0f;
  s.elasticity[1] = 4.0f;
  s.elasticity[2] = 0.0f;
  s.position.set(2, Vec3(0, 1, 0));
  s.velocity.set(1, Vec3(0.2f, 0.7f, 0));  // only the x part lies along the spring
  forces(p, StepUniforms{}, p.pressureCoefficient, film.topology, s, 0);
  // Spring 0-1: stiffness (2 + 4) / 2 = 3, stretch 0.1 -> 0.3 along +x; damping 0.5 * 0.2 = 0.1 along +x.
  // Spring 0-2 is at rest length and its stiffness (2 + 0) / 2 pulls nothing.
  EXPECT_NEAR(s.force.x[0], 0.4f, kFormulaTolerance);
  EXPECT_NEAR(s.force.y[0], 0.0f, kFormulaTolerance);
}

TEST(Forces, Eq9AirPushesAlongTheNormalOnly) {
  Params p;
  p.gravityY = 0.0f;
  p.airDrag = 0.0f;
  p.airPressureGain = 2.0f;
  Film film = test::makeHexagon(p);
  State& s = film.state;
  computeGeometry(film.topology, s);
  s.elasticity.assign(s.size(), 0.0f);
  s.airFlow.set(0, Vec3(5, 0, -1));    // transferred air: only -1 along the normal +z counts
  s.airInflow.set(0, Vec3(0, 3, -2));  // direct inflow: -2 along the normal
  forces(p, StepUniforms{}, p.pressureCoefficient, film.topology, s, 0);
  const float expected = 2.0f * (-1.0f - 2.0f) * s.voronoiArea[0];
  EXPECT_NEAR(s.force.z[0], expected, std::abs(expected) * kFormulaTolerance);
  EXPECT_NEAR(s.force.x[0], 0.0f, kFormulaTolerance);
  EXPECT_NEAR(s.force.y[0], 0.0f, kFormulaTolerance);
}

TEST(Pressure, Eq11BoylesLaw) {
  Params p;
  p.pressureCoefficient = 1010.0f;
  EXPECT_FLOAT_EQ(boylePressure(p, 2.0f, 1.0f), 2020.0f);
  EXPECT_FLOAT_EQ(boylePressure(p, 2.0f, 4.0f), 505.0f);
}

// The air's energy is zero at V_0, positive either side, and its derivative is minus the excess pressure (the
// force Boyle's law puts on the film is its gradient). Central difference over 1e-6 of V in double: its error,
// of order the third derivative times 1e-12, is far below the 1e-6 relative bound.
TEST(Pressure, BoyleGasEnergyIsThePotentialOfTheExcessPressure) {
  const Params p;
  EXPECT_EQ(boyleGasEnergy(p, 0.5, 0.5), 0.0);
  for (const double v : {0.3, 0.45, 0.55, 0.8}) {
    EXPECT_GT(boyleGasEnergy(p, 0.5, v), 0.0) << "V = " << v;
    const double dv = 1e-6 * v;
    const double slope = (boyleGasEnergy(p, 0.5, v + dv) - boyleGasEnergy(p, 0.5, v - dv)) / (2 * dv);
    const double excess = p.pressureCoefficient * 0.5 / v - p.pressureCoefficient;
    EXPECT_NEAR(slope, -excess, 1e-6 * p.pressureCoefficient) << "V = " << v;
  }
}

TEST(Integration, Eq12And13SemiImplicitEuler) {
  const Params p;
  Film film = test::makeHexagon(p);
  State& s = film.state;
  s.mass[0] = 2.0f;
  s.velocity.set(0, Vec3(1, 0, 0));
  s.force.set(0, Vec3(0, 4, 0));
  StepUniforms u;
  u.dt = 0.5f;
  integrate(u, film.topology, s, 0);
  // v' = v + h f / m = (1, 1, 0); x' = x + h v' = (0.5, 0.5, 0): the new velocity moves the particle.
  EXPECT_EQ(s.velocity.get(0), Vec3(1, 1, 0));
  EXPECT_EQ(s.position.get(0), Vec3(0.5f, 0.5f, 0));
}

TEST(Integration, BoundaryParticlesFollowTheWireFrame) {
  const Params p;
  Film film = test::makeHexagon(p);
  State& s = film.state;
  ASSERT_TRUE(film.topology.boundary[1]);
  s.wireParam[1] = 0.25f;
  StepUniforms u;
  u.dt = 0.1f;
  WireFrame ring;
  ring.kind = ToolKind::Ring;
  ring.center = Vec3(0, 0, 1);
  ring.halfWidth = ring.depth = 2.0f;
  setWireNext(u, ring);
  integrate(u, film.topology, s, 1);
  const Vec3 expected = wirePoint(ring, 0.25f);
  EXPECT_EQ(s.position.get(1), expected);
  EXPECT_NEAR((s.velocity.get(1) - (expected - Vec3(1, 0, 0)) / 0.1f).norm(), 0.0f, 1e-5f);
}

TEST(Reduction, TreeSumHasAFixedPairwiseShape) {
  EXPECT_FLOAT_EQ(treeSum({}), 0.0f);
  EXPECT_FLOAT_EQ(treeSum({1, 2, 3, 4, 5}), 15.0f);
  // ((1e8 + 1) + (-1e8 + 1)) loses both ones in float; a left-to-right sum would keep one of them.
  EXPECT_FLOAT_EQ(treeSum({1e8f, 1.0f, -1e8f, 1.0f}), 0.0f);
}

TEST(Reduction, TreeSumAddsFourPairsAtATimeAsOneAtATime) {
  // treeSumInPlace adds eight elements into four sums at once: every level must hold what the pairwise sums one at a
  // time give, bit for bit, for every length's tail of pairs and odd last element.
  std::mt19937 random(11);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (size_t n : {1, 2, 3, 7, 8, 9, 15, 16, 17, 31, 33, 100, 1001, 24013}) {
    std::vector<float> v(n);
    for (float& x : v) x = value(random) * std::exp2(value(random) * 20.0f);  // magnitudes over 12 decades
    std::vector<float> level = v;
    while (level.size() > 1) {
      std::vector<float> next;
      for (size_t k = 0; k + 1 < level.size(); k += 2) next.push_back(level[k] + level[k + 1]);
      if (level.size() % 2 == 1) next.push_back(level.back());
      level = next;
    }
    EXPECT_EQ(treeSumInPlace(v), level[0]) << n << " elements";
  }
}

}  // namespace
}  // namespace gb

namespace gb {
namespace {

TEST(Integration, TheFloorStopsAFallingParticleButLetsItSlide) {
  const Params p;
  Film film = test::makeHexagon(p);
  State& s = film.state;
  s.position.set(0, Vec3(0, 0.01f, 0));
  s.velocity.set(0, Vec3(0.5f, -2.0f, 0));
  s.force.set(0, Vec3::Zero());
  StepUniforms u;
  u.dt = 0.01f;
  integrate(u, film.topology, s, 0);
  EXPECT_EQ(s.position.y[0], 0.0f);
  EXPECT_EQ(s.velocity.y[0], 0.0f);
  EXPECT_FLOAT_EQ(s.velocity.x[0], 0.5f);
  EXPECT_FLOAT_EQ(s.position.x[0], 0.005f);
}

}  // namespace
}  // namespace gb
