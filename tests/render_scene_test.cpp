// What the renderer draws, built on the CPU (host/render_scene.h, host/film_swirls.h): the camera that keeps the
// film framed, the film's drawn thickness swirls, the hole rims and the outdoor sky. No Vulkan.
#include "host/render_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "host/film_swirls.h"

namespace gb {
namespace {

// Fraction of the image height spanned by the living particles seen through `camera`.
float heightFractionOnScreen(const OrbitCamera& camera, const State& s) {
  const Eigen::Matrix4f vp = camera.viewProjection(16.0f / 9.0f);
  float lo = 1e9f, hi = -1e9f;
  for (size_t i = 0; i < s.size(); ++i) {
    const Eigen::Vector4f clip = vp * Eigen::Vector4f(s.position.x[i], s.position.y[i], s.position.z[i], 1.0f);
    lo = std::min(lo, clip.y() / clip.w());
    hi = std::max(hi, clip.y() / clip.w());
  }
  return 0.5f * (hi - lo);  // clip y spans 2 over the image
}

TEST(FilmFraming, KeepsABubbleAtAboutHalfTheImageHeightAndFollowsItSmoothly) {
  const Params params;
  Film film = generateSphere(params, Vec3(0.0f, 1.2f, 0.0f), 0.5f, 3);
  FilmFraming framing;
  const OrbitCamera base;
  OrbitCamera camera = framing.update(base, film.state, 0.02f);
  // The outline spans heightFraction (0.55) of the image height: the distance is found to 0.01% on the particles'
  // projections, so within 1e-4 (measured within 1e-5).
  EXPECT_NEAR(heightFractionOnScreen(camera, film.state), 0.55f, 1e-4f);
  EXPECT_FLOAT_EQ(camera.yaw, base.yaw) << "the framing keeps the camera's direction";
  EXPECT_NEAR((camera.target - Vec3(0.0f, 1.2f, 0.0f)).norm(), 0.0f, 0.02f);

  // The bubble jumps 1 m and doubles in size: one frame later the camera has moved only a little (eased, no
  // jump), three seconds later it frames the bubble again.
  for (size_t i = 0; i < film.state.size(); ++i)
    film.state.position.set(i, Vec3(1.0f, 1.2f, 0.0f) + 2.0f * (film.state.position.get(i) - Vec3(0.0f, 1.2f, 0.0f)));
  camera = framing.update(base, film.state, 0.02f);
  EXPECT_LT(camera.target.x(), 0.1f);
  for (int f = 0; f < 150; ++f) camera = framing.update(base, film.state, 0.02f);
  EXPECT_NEAR(camera.target.x(), 1.0f, 0.01f);
  // Eased for 3 s, the distance is within 0.01 of the framing (measured 0.0008 over it).
  EXPECT_NEAR(heightFractionOnScreen(camera, film.state), 0.55f, 0.01f);

  // A burst film (nothing alive) leaves the camera where it was.
  std::fill(film.state.alive.begin(), film.state.alive.end(), 0u);
  const OrbitCamera after = framing.update(base, film.state, 0.02f);
  EXPECT_FLOAT_EQ(after.distance, camera.distance);
}

TEST(FilmFraming, KeepsADriftingBubbleCentred) {
  // A bubble flying at the default stroke's 1.7 m/s for 2 s: the camera's target stays within 5 cm of its centre
  // (a first-order follower without the velocity lead trails by speed x easing = 0.85 m, the film drifting off
  // the picture's side).
  const Params params;
  Film film = generateSphere(params, Vec3(0.0f, 1.2f, 0.0f), 0.5f, 3);
  FilmFraming framing;
  const OrbitCamera base;
  const Vec3 step(0.0f, 0.0f, 1.7f * 0.02f);
  OrbitCamera camera;
  for (int f = 0; f < 100; ++f) {
    for (size_t i = 0; i < film.state.size(); ++i) film.state.position.set(i, film.state.position.get(i) + step);
    camera = framing.update(base, film.state, 0.02f);
  }
  const Vec3 centre(0.0f, 1.2f, 100.0f * step.z());
  EXPECT_LT((camera.target - centre).norm(), 0.05f) << "target " << camera.target.transpose();
}

TEST(FilmFraming, AFilmWithNoExtentOnTheImageIsFramedFromTheNearestDistance) {
  // One living particle, or a film along the camera's axis, fits the picture from any distance: the camera comes
  // to minDistance (1 m), not into the film and not away to the bracket's far end.
  Film film = generateSphere(Params{}, Vec3(0.0f, 1.2f, 0.0f), 0.5f, 2);
  std::fill(film.state.alive.begin() + 1, film.state.alive.end(), 0u);
  FilmFraming framing;
  EXPECT_FLOAT_EQ(framing.update(OrbitCamera{}, film.state, 0.02f).distance, FilmFraming::Options{}.minDistance);
  // Two particles 0.6 m before and behind the centre on the camera's axis: the nearest distance that keeps them
  // in front of the camera is 0.65 m, under minDistance.
  const OrbitCamera base;
  const Vec3 axis = (base.position() - base.target).normalized();
  film.state.alive[1] = 1u;
  film.state.position.set(0, Vec3(0.0f, 1.2f, 0.0f) + 0.6f * axis);
  film.state.position.set(1, Vec3(0.0f, 1.2f, 0.0f) - 0.6f * axis);
  FilmFraming endOn;
  EXPECT_FLOAT_EQ(endOn.update(base, film.state, 0.02f).distance, FilmFraming::Options{}.minDistance);
}

TEST(FilmFraming, KeepsALongBagWithinTheImageWidth) {
  // A bag 4 m long and 1 m high seen side-on: framed by its length, the outline spans at most widthFraction (0.8)
  // of a 16:9 image's width (within 1e-4: the distance is found to 0.01%), and so less than half the height.
  Film film = generateSphere(Params{}, Vec3(0.0f, 1.2f, 0.0f), 0.5f, 3);
  for (size_t i = 0; i < film.state.size(); ++i) {
    const Vec3 p = film.state.position.get(i) - Vec3(0.0f, 1.2f, 0.0f);
    film.state.position.set(i, Vec3(4.0f * p.x(), 1.2f + p.y(), p.z()));
  }
  OrbitCamera base;
  base.yaw = 0.0f;  // looking along -z: the bag's length across the picture
  FilmFraming framing;
  const OrbitCamera camera = framing.update(base, film.state, 0.02f);
  const Eigen::Matrix4f vp = camera.viewProjection(16.0f / 9.0f);
  float lo = 1e9f, hi = -1e9f;
  for (size_t i = 0; i < film.state.size(); ++i) {
    const Eigen::Vector4f clip =
        vp * Eigen::Vector4f(film.state.position.x[i], film.state.position.y[i], film.state.position.z[i], 1.0f);
    lo = std::min(lo, clip.x() / clip.w());
    hi = std::max(hi, clip.x() / clip.w());
  }
  EXPECT_NEAR(0.5f * (hi - lo), 0.8f, 1e-4f);
  EXPECT_LT(heightFractionOnScreen(camera, film.state), 0.5f);
}

TEST(FilmSwirls, LogVariationHasZeroMeanAndUnitSpread) {
  // Over points spread across many swirls: mean 0 within 0.05, standard deviation 1 within 15% (kFractalSpread
  // is this measurement, rounded).
  double sum = 0, squares = 0;
  const int n = 100000;
  for (int k = 0; k < n; ++k) {
    const Vec3 p(0.0137f * static_cast<float>(k % 317), 0.0191f * static_cast<float>(k / 317), 0.3f);
    const double g = FilmSwirls::logVariation(p, 0.0f);
    sum += g;
    squares += g * g;
  }
  const double mean = sum / n, spread = std::sqrt(squares / n - mean * mean);
  std::printf("swirl field: mean %.3f, standard deviation %.3f\n", mean, spread);
  EXPECT_NEAR(mean, 0.0, 0.05);
  EXPECT_NEAR(spread, 1.0, 0.15);
}

TEST(FilmSwirls, FactorsMoveWithTheFilmAndANewFilmIsSeededAgain) {
  const Params params;
  Film film = generateSphere(params, Vec3(0.0f, 1.2f, 0.0f), 3.0f, 4);
  FilmSwirls swirls(0.45f);
  const std::vector<float> first = swirls.update(film.state);
  // Mean factor 1 (the simulated thickness is the mean): within 5% over a sphere of 3 m radius, about 1800
  // swirls of 25 cm (a sampling error of about 1%).
  EXPECT_NEAR(std::accumulate(first.begin(), first.end(), 0.0) / static_cast<double>(first.size()), 1.0, 0.05);
  // The film moves and stretches (every particle 0.3 m up, scaled 1.5x), no time passes: the same factors,
  // since each particle keeps its material coordinate.
  for (size_t i = 0; i < film.state.size(); ++i)
    film.state.position.set(i, Vec3(0.0f, 1.5f, 0.0f) + 1.5f * (film.state.position.get(i) - Vec3(0.0f, 1.2f, 0.0f)));
  EXPECT_EQ(swirls.update(film.state), first);
  // Time passes: the swirls turn, slowly (factors change, but not all of them by much in 0.1 s).
  for (float& t : film.state.lifetime) t += 0.1f;
  const std::vector<float> later = swirls.update(film.state);
  double change = 0;
  for (size_t i = 0; i < later.size(); ++i) change += std::abs(std::log(later[i] / first[i]));
  change /= static_cast<double>(later.size());
  EXPECT_GT(change, 1e-4);
  EXPECT_LT(change, 0.1);
  // A new film made in its place (lifetimes back to 0) is seeded from where its particles are now.
  for (float& t : film.state.lifetime) t = 0.0f;
  EXPECT_NE(swirls.update(film.state), first);
}

TEST(HoleRims, AnIntactFilmHasNoneAndATornOneHasItsHoleEdge) {
  const Params params;
  Film bubble = generateSphere(params, Vec3(0.0f, 1.2f, 0.0f), 0.5f, 2);
  EXPECT_TRUE(holeRimEdges(bubble).empty()) << "a closed bubble has no rim";
  // Tear out the triangles around particle 0: the edges of its one-ring become the rim.
  std::vector<uint32_t> kept;
  size_t removed = 0;
  for (size_t t = 0; t < bubble.topology.triangles.size(); t += 3) {
    const uint32_t* tri = &bubble.topology.triangles[t];
    if (tri[0] == 0 || tri[1] == 0 || tri[2] == 0)
      ++removed;
    else
      kept.insert(kept.end(), tri, tri + 3);
  }
  bubble.topology.triangles = kept;
  EXPECT_EQ(holeRimEdges(bubble).size(), 2 * removed) << "one rim edge per removed triangle around a vertex";
}

TEST(SkyEnvironment, IsBrightAboveNeutralBelowWithTheSunAsKeyLight) {
  const EnvironmentImage sky = skyEnvironment(256);
  const std::array<Vec3, 2> means = hemisphereMeans(sky);
  EXPECT_GT(means[0].mean(), 0.4f) << "a bright sky";
  EXPECT_GT(means[0].z(), means[0].x()) << "blue";
  EXPECT_LT(means[1].mean(), means[0].mean());
  EXPECT_GT(sky.keyLight.y(), 0.3f) << "the sun is up";
  // Below the horizon, the ground as the floor prop is lit (props.frag: its neutral albedo times the sky's mean
  // radiance and the sun), so the floor meets it without a seam; tolerance: float rounding of the means.
  const Vec3 lit = groundAlbedo().cwiseProduct(means[0] + Vec3::Constant(sky.keyStrength * sky.keyLight.y()));
  EXPECT_LT((means[1] - lit).norm(), 1e-4f);
  EXPECT_LT((horizonRadiance(sky) - lit).norm(), 1e-4f) << "no haze band between the floor's edge and the ground";
  // Lit by the blue sky it is a little bluer than its albedo, as sunlit ground is, but still grey: channels within
  // 25% of each other (measured 1.22).
  EXPECT_LT(means[1].maxCoeff() / means[1].minCoeff(), 1.25f);
}

TEST(FilmFraming, LooksUpAtAFilmFromAboveTheFloorNeverUnderIt) {
  // The default camera looks up at the film (negative pitch). A bubble sinking to the floor would take the eye
  // under it: the pitch is raised instead so that the eye stays minEyeHeight above the ground, and the framing
  // still spans 0.55 of the image height (within 0.01, as above).
  const Params params;
  const Film low = generateSphere(params, Vec3(0.0f, 0.45f, 0.0f), 0.4f, 3);
  FilmFraming framing;
  const OrbitCamera base;
  ASSERT_LT(base.pitch, 0.0f) << "the default camera looks up";
  const OrbitCamera camera = framing.update(base, low.state, 0.02f);
  EXPECT_NEAR(camera.position().y(), FilmFraming::Options{}.minEyeHeight, 1e-3f);
  EXPECT_GT(camera.pitch, base.pitch);
  EXPECT_NEAR(heightFractionOnScreen(camera, low.state), 0.55f, 0.01f);
  // High up the base pitch is kept.
  const Film high = generateSphere(params, Vec3(0.0f, 1.5f, 0.0f), 0.4f, 3);
  FilmFraming again;
  EXPECT_FLOAT_EQ(again.update(base, high.state, 0.02f).pitch, base.pitch);
}

// Luminance of the environment's texel in direction d (nearest texel; the parameterisation of texelDirection).
float luminanceToward(const EnvironmentImage& env, const Vec3& d) {
  const float u = 0.5f + std::atan2(d.x(), -d.z()) / (2.0f * std::numbers::pi_v<float>);
  const float v = std::acos(std::clamp(d.y(), -1.0f, 1.0f)) / std::numbers::pi_v<float>;
  const int col = std::clamp(static_cast<int>(u * static_cast<float>(env.width)), 0, env.width - 1);
  const int row = std::clamp(static_cast<int>(v * static_cast<float>(env.height)), 0, env.height - 1);
  const float* c = &env.rgb[3 * (static_cast<size_t>(row) * static_cast<size_t>(env.width) + col)];
  return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

TEST(SkyEnvironment, AWoodStandsBehindTheStageDarkerThanTheSunlitGround) {
  // Ahead of the default camera, up to 20 degrees (where the film is seen from it), the wood: at most half as bright
  // as the sunlit ground below the horizon (a canopy reflects about 4% of visible light, the ground 30%; measured
  // 0.03-0.15 of it, printed: sunlit clumps, shaded gaps, the understory darker near the ground); above it, at 45
  // degrees, the blue sky again, brighter than the ground; behind the camera no wood: sky and distant hills, more
  // than twice as bright as the wood.
  const EnvironmentImage sky = skyEnvironment(1024);
  const OrbitCamera camera;
  const Vec3 ahead = Vec3(camera.target - camera.position()).cwiseProduct(Vec3(1, 0, 1)).normalized();
  const auto toward = [&](const Vec3& horizontal, float elevationDegrees) {
    const float e = elevationDegrees * std::numbers::pi_v<float> / 180.0f;
    return luminanceToward(sky, std::cos(e) * horizontal + std::sin(e) * Vec3::UnitY());
  };
  const float ground = toward(ahead, -10.0f);
  const Vec3 right = ahead.cross(Vec3::UnitY());
  for (float side : {-0.5f, 0.0f, 0.5f})  // across the picture: tan 0.5 is 27 degrees to either side
    for (float elevation : {1.0f, 5.0f, 10.0f, 15.0f, 20.0f}) {
      const Vec3 h = (ahead + side * right).normalized();
      std::printf("side %+.1f, %2.0f degrees up: %.2f of the ground's luminance\n", side, elevation,
                  toward(h, elevation) / ground);
      EXPECT_LT(toward(h, elevation), 0.5f * ground) << "side " << side << ", " << elevation << " degrees up";
    }
  EXPECT_GT(toward(ahead, 45.0f), ground) << "the sky above the trees";
  EXPECT_GT(toward(-ahead, 10.0f), 2.0f * toward(ahead, 10.0f)) << "open land behind the camera";
}

}  // namespace
}  // namespace gb
