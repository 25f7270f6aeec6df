// The live window's camera (app/show/live_camera.h): it keeps a drifting free bubble in the picture without jumps, lets
// the user take over, and Home hands control back without a jump.
#include "app/show/live_camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "model/film.h"

namespace gb {
namespace {

constexpr float kAspect = 16.0f / 9.0f;
constexpr float kFrame = 0.02f;

// The largest |x| or |y| of the living particles in the picture (1: on its edge; infinite: one is behind the camera).
float farthestInPicture(const OrbitCamera& camera, const State& s) {
  float farthest = 0.0f;
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s.alive[i]) continue;
    const Eigen::Vector2f p = pictureCoordinates(camera, kAspect, s.position.get(i));
    if (!p.allFinite()) return INFINITY;  // behind the camera
    farthest = std::max({farthest, std::abs(p.x()), std::abs(p.y())});
  }
  return farthest;
}

void drift(State& s, const Vec3& step) {
  for (size_t i = 0; i < s.size(); ++i) s.position.set(i, s.position.get(i) + step);
}

// A free bubble 1 m across, blown forward and drifting to the side and down as the default one does, for 6 s.
Film driftingBubble() { return generateSphere(Params{}, Vec3(0.0f, 1.6f, 1.0f), 0.5f, 3); }
const Vec3 kDrift(1.2f, -0.15f, 1.0f);  // m/s

TEST(LiveCamera, KeepsADriftingFreeBubbleInThePictureWithoutJumps) {
  Film film = driftingBubble();
  const OrbitCamera base;
  LiveCamera camera(base, true, kAspect);
  OrbitCamera user = base;
  const WandState wands;
  OrbitCamera last = camera.update(film.state, wands, kFrame, user, false);
  float farthest = 0.0f, largestMove = 0.0f;
  for (int f = 0; f < 300; ++f) {
    drift(film.state, kFrame * kDrift);
    const OrbitCamera view = camera.update(film.state, wands, kFrame, user, false);
    farthest = std::max(farthest, farthestInPicture(view, film.state));
    largestMove = std::max(largestMove, (view.position() - last.position()).norm());
    last = view;
  }
  // Every particle of the bubble stays inside the picture all along: the framing holds its outline at 55% of the
  // image height, and the drift's lag adds a little (0.65 of the half-height measured); 0.75 leaves room for that.
  EXPECT_LT(farthest, 0.75f);
  // No jumps: the eye moves at most twice the bubble's own way per frame (the lead and the easing add to it: 1.15
  // times measured).
  EXPECT_LT(largestMove, 2.0f * kDrift.norm() * kFrame);
  // The scene's fixed camera loses it: the check above can fail.
  EXPECT_GT(farthestInPicture(base, film.state), 1.0f);
}

TEST(LiveCamera, TheUserTakesOverAndHomeHandsBackWithoutAJump) {
  Film film = driftingBubble();
  const OrbitCamera base;
  LiveCamera camera(base, true, kAspect), untouched(base, true, kAspect);
  OrbitCamera user = base, spare = base;
  const WandState wands;
  for (int f = 0; f < 20; ++f) {
    drift(film.state, kFrame * kDrift);
    (void)untouched.update(film.state, wands, kFrame, spare, false);
    (void)camera.update(film.state, wands, kFrame, user, false);
  }
  // The window's camera is the one shown, so that a drag starts from it; the drag turns it by 1 rad.
  user.yaw += 1.0f;
  user.distance *= 1.5f;
  OrbitCamera held = user;
  drift(film.state, kFrame * kDrift);
  (void)untouched.update(film.state, wands, kFrame, spare, false);
  EXPECT_EQ(camera.update(film.state, wands, kFrame, user, true).yaw, held.yaw);
  EXPECT_TRUE(camera.userControlled());
  for (int f = 0; f < 50; ++f) {  // the user's camera stays put while the bubble drifts on
    drift(film.state, kFrame * kDrift);
    (void)untouched.update(film.state, wands, kFrame, spare, false);
    const OrbitCamera view = camera.update(film.state, wands, kFrame, user, false);
    EXPECT_EQ(view.target, held.target);
    EXPECT_EQ(view.distance, held.distance);
  }
  camera.home();
  EXPECT_FALSE(camera.userControlled());
  OrbitCamera last = held;
  float largestTurn = 0.0f;
  for (int f = 0; f < 60; ++f) {
    drift(film.state, kFrame * kDrift);
    const OrbitCamera followed = untouched.update(film.state, wands, kFrame, spare, false);
    const OrbitCamera view = camera.update(film.state, wands, kFrame, user, false);
    largestTurn = std::max(largestTurn, std::abs(view.yaw - last.yaw));
    last = view;
    // After the hand-back (1 s) the camera is the follow camera's to within float rounding.
    if (static_cast<float>(f + 1) * kFrame >= LiveCamera::kHandBack + 1e-4f) {
      EXPECT_NEAR(view.yaw, followed.yaw, 1e-5f) << f;
      EXPECT_LT((view.target - followed.target).norm(), 1e-4f) << f;
      EXPECT_NEAR(view.distance, followed.distance, 1e-4f) << f;
    }
  }
  // The 1 rad turn back is spread over the second: a smoothstep's steepest frame takes 1.5 x 1 rad x 0.02 s / 1 s.
  EXPECT_LT(largestTurn, 1.5f * 1.0f * kFrame / LiveCamera::kHandBack + 1e-3f);
}

TEST(LiveCamera, AnEmptyStageFramesTheWandsWhereTheNextFilmWillHang) {
  Film film = driftingBubble();
  std::fill(film.state.alive.begin(), film.state.alive.end(), 0u);  // burst and gone
  const OrbitCamera base;
  LiveCamera camera(base, true, kAspect);
  OrbitCamera user = base;
  WandState wands;
  wands.leftPosition = Vec3(2.5f, 2.0f, 3.0f);  // where a stroke ended, far from the scene camera's target
  wands.rightPosition = Vec3(3.5f, 2.0f, 3.0f);
  OrbitCamera view;
  for (int f = 0; f < 150; ++f) view = camera.update(film.state, wands, kFrame, user, false);
  // Framed on the tips and 0.8 m below them: the target at their middle, 0.4 m down (3 s is six easing times).
  EXPECT_LT((view.target - Vec3(3.0f, 1.6f, 3.0f)).norm(), 0.05f) << view.target.transpose();
}

TEST(LiveCamera, AFixedCameraStaysTheScenesAndHomeReturnsToIt) {
  Film film = driftingBubble();
  OrbitCamera base;
  base.yaw = 0.3f;
  LiveCamera camera(base, false, kAspect);
  OrbitCamera user = base;
  const WandState wands;
  EXPECT_EQ(camera.update(film.state, wands, kFrame, user, false).target, base.target);
  user.pitch = 0.5f;
  (void)camera.update(film.state, wands, kFrame, user, true);
  camera.home();
  OrbitCamera view;
  for (int f = 0; f < 60; ++f) view = camera.update(film.state, wands, kFrame, user, false);
  EXPECT_NEAR(view.pitch, base.pitch, 1e-6f);
  EXPECT_NEAR(view.yaw, base.yaw, 1e-6f);
}

}  // namespace
}  // namespace gb
