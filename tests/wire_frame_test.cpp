#include <gtest/gtest.h>

#include <numbers>

#include "wire_frame.h"

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
  EXPECT_NEAR((framePoint(f, 0.0f) - w.leftPosition).norm(), 0.0f, 1e-6f);
  EXPECT_NEAR((framePoint(f, 1.0f) - w.rightPosition).norm(), 0.0f, 1e-6f);
  EXPECT_NEAR((framePoint(f, 1.5f) - Vec3(0, 0.8f, 0)).norm(), 0.0f, 1e-5f);  // bottom of the loop
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
  for (float u : {0.0f, 0.2f, 0.5f, 0.9f}) EXPECT_NEAR((framePoint(f, u) - w.rightPosition).norm(), 0.3f, 1e-6f);
  EXPECT_NEAR(f.area(), kPi * 0.09f, 1e-6f);
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
