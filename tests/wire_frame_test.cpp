#include "model/wire_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gb {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

TEST(WireFrame, HangingStringIsAHalfEllipseAndItsInverse) {
  // a = b: half a circle of radius a.
  EXPECT_NEAR(hangingStringLength(0.5f, 0.5f), kPi * 0.5f, 1e-5f);
  // b = 0: the string lies along the tips, length 2a (Ramanujan's formula is exact there to 0.5%).
  EXPECT_NEAR(hangingStringLength(0.5f, 0.0f), 1.0f, 5e-3f);
  for (float depth : {0.1f, 0.4f, 0.8f, 2.0f})
    EXPECT_NEAR(hangingDepth(0.5f, hangingStringLength(0.5f, depth)), depth, 1e-5f * (1 + depth));
  EXPECT_EQ(hangingDepth(0.5f, 0.5f), 0.0f);  // a string shorter than the tip separation is taut
}

TEST(WireFrame, TwoWandLoopPassesThroughBothTipsAndHangsDown) {
  WandState w;
  w.leftPosition = Vec3(-0.5f, 1.6f, 0);
  w.rightPosition = Vec3(0.5f, 1.6f, 0);
  const float length = hangingStringLength(0.5f, 0.8f);
  const WireFrame f = makeWireFrame(WandTool{}, w, length, Vec3(0, -9.81f, 0));
  EXPECT_NEAR((wirePoint(f, 0.0f) - w.leftPosition).norm(), 0.0f, 1e-6f);
  EXPECT_NEAR((wirePoint(f, 1.0f) - w.rightPosition).norm(), 0.0f, 1e-6f);
  EXPECT_NEAR((wirePoint(f, 1.5f) - Vec3(0, 0.8f, 0)).norm(), 0.0f, 1e-5f);  // bottom of the loop
  EXPECT_NEAR(f.area(), 0.5f * kPi * 0.5f * 0.8f, 1e-5f);
  EXPECT_NEAR(f.height(), 0.8f, 1e-5f);
  // Bringing the tips together lets the same string hang deeper.
  w.leftPosition.x() = -0.3f;
  w.rightPosition.x() = 0.3f;
  EXPECT_GT(makeWireFrame(WandTool{}, w, length, Vec3(0, -9.81f, 0)).depth, 0.8f);
}

TEST(WireFrame, RingIsCentredOnTheRightHand) {
  WandTool tool;
  tool.kind = ToolKind::Ring;
  tool.ringRadius = 0.3f;
  WandState w;
  w.rightPosition = Vec3(1, 2, 3);
  const WireFrame f = makeWireFrame(tool, w, 0.0f, Vec3(0, -9.81f, 0));
  for (float u : {0.0f, 0.2f, 0.5f, 0.9f}) EXPECT_NEAR((wirePoint(f, u) - w.rightPosition).norm(), 0.3f, 1e-6f);
  EXPECT_NEAR(f.area(), kPi * 0.09f, 1e-6f);
}

// One tip passes over the other in the x-y plane: the span turns through the vertical in 0.4 s, frames of 0.02 s.
// Gravity projected off the span turns over (180 degrees) in the frame where the span passes the vertical; the
// swung loop never turns more than rate x h in a frame (1e-4 rad: float rounding of the rotation) and hangs
// straight towards gravity again once the swing has had time (a half turn at 6 rad/s takes 0.52 s).
TEST(WireFrame, TheLoopSwingsOverAtABoundedRateWhenOneTipPassesAboveTheOther) {
  const Vec3 gravity(0, -9.81f, 0);
  const float h = 0.02f, maxTurn = 6.0f * h;
  const auto spanAt = [&](int frame) {
    const float angle = 0.25f * kPi + 0.5f * kPi * std::min(1.0f, static_cast<float>(frame) / 20.0f);  // 45 -> 135 deg
    return Vec3(std::cos(angle), std::sin(angle), 0.0f);
  };
  const auto towardsGravity = [&](const Vec3& axis) { return Vec3((gravity - gravity.dot(axis) * axis).normalized()); };
  Vec3 down = towardsGravity(spanAt(0));
  float largestGravityTurn = 0, largestSwingTurn = 0;
  for (int frame = 1; frame <= 60; ++frame) {
    const Vec3 axis = spanAt(frame);
    const Vec3 swung = swingLoop(down, axis, gravity, maxTurn);
    EXPECT_NEAR(swung.dot(axis), 0.0f, 1e-6f);
    EXPECT_NEAR(swung.norm(), 1.0f, 1e-6f);
    largestSwingTurn = std::max(largestSwingTurn, std::acos(std::clamp(swung.dot(down), -1.0f, 1.0f)));
    largestGravityTurn =
        std::max(largestGravityTurn,
                 std::acos(std::clamp(towardsGravity(axis).dot(towardsGravity(spanAt(frame - 1))), -1.0f, 1.0f)));
    down = swung;
  }
  EXPECT_GT(largestGravityTurn, 0.9f * kPi);  // the stateless rule turns over in one frame
  // The swing is bounded per frame, plus what the span's own turn (pi/40 per frame) carries the loop along.
  EXPECT_LT(largestSwingTurn, maxTurn + 0.5f * kPi / 20.0f + 1e-4f);
  EXPECT_GT(down.dot(towardsGravity(spanAt(60))), 1.0f - 1e-5f);  // hanging down again 0.8 s after the pass
}

TEST(WireFrame, InterpolatesWandStates) {
  WandState a, b;
  b.leftPosition = Vec3(2, 0, 0);
  b.rightVelocity = Vec3(0, 4, 0);
  const WandState m = interpolate(a, b, 0.25f);
  EXPECT_EQ(m.leftPosition, Vec3(0.5f, 0, 0));
  EXPECT_EQ(m.rightVelocity, Vec3(0, 1, 0));
}

}  // namespace
}  // namespace gb
