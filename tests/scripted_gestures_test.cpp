#include "capture/scripted_gestures.h"

#include <gtest/gtest.h>

namespace gb {
namespace {

TEST(ScriptedGestures, EveryGestureStartsAtRestAndItsVelocityIsTheDerivativeOfItsPosition) {
  const GestureOptions o;
  for (const std::string& name : gestureNames()) {
    const Gesture g = gestureFromName(name);
    const WandState start = gestureAt(g, o, 0.0);
    EXPECT_EQ(start.leftVelocity, Vec3::Zero()) << name;
    for (double t = 0.6; t < o.start + o.duration; t += 0.37) {
      const double h = 1e-3;
      const WandState a = gestureAt(g, o, t - h), b = gestureAt(g, o, t + h), w = gestureAt(g, o, t);
      const Vec3 left = (b.leftPosition - a.leftPosition) / static_cast<float>(2 * h);
      const Vec3 right = (b.rightPosition - a.rightPosition) / static_cast<float>(2 * h);
      // Central differences in float32 positions: errors of a few mm/s.
      EXPECT_LT((left - w.leftVelocity).norm(), 0.02f) << name << " t = " << t;
      EXPECT_LT((right - w.rightVelocity).norm(), 0.02f) << name << " t = " << t;
    }
  }
}

TEST(ScriptedGestures, CirclesMoveTheLeftWandOnlyForFigure10b) {
  const GestureOptions o;
  const WandState straight = gestureAt(Gesture::Straight, o, 1.6), circle = gestureAt(Gesture::CircleLeft, o, 1.6);
  EXPECT_GT((circle.leftPosition - straight.leftPosition).norm(), 0.01f);
  EXPECT_EQ(circle.rightPosition, straight.rightPosition);
  EXPECT_THROW(gestureFromName("spiral"), std::invalid_argument);
}

}  // namespace
}  // namespace gb
