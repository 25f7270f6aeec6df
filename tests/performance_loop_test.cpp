// The live show's performance loop (app/show/performance_loop.h): a script or a recording plays again once the stage is
// empty, the wands going back to its start without a jump.
#include "app/show/performance_loop.h"

#include <gtest/gtest.h>

#include "capture/scripted_gestures.h"

namespace gb {
namespace {

using Action = PerformanceLoop::Action;
constexpr double kFrame = 0.02;

// The default performance's end pose (the giant stroke, closed and lifted) and its start pose.
WandState endPose() {
  GestureOptions g;
  g.speed = 1.7f;
  g.duration = 2.0f;
  return gestureAt(Gesture::Giant, g, 10.0);
}
WandState startPose() { return gestureAt(Gesture::Giant, GestureOptions{}, 0.0); }

TEST(PerformanceLoop, PlaysWhileTheWandsHoldAFilm) {
  PerformanceLoop loop(2.0);
  // The performance is over but the film still hangs on the wands: the stage is not empty, nothing loops.
  for (double t = 0; t < 10; t += kFrame) EXPECT_EQ(loop.next(t, t > 2.5, false, -1), Action::Play) << t;
  EXPECT_FALSE(loop.looping());
}

TEST(PerformanceLoop, ReturnsOnceTheBubbleFliesFreeAndDipsAfterTheEmptyStagesPause) {
  const double autoDip = 1.0;
  PerformanceLoop loop(autoDip);
  EXPECT_EQ(loop.next(2.0, false, true, -1), Action::Play);  // free, but the performance still plays
  ASSERT_EQ(loop.next(2.6, true, true, -1), Action::StartReturn);
  const WandState from = endPose(), to = startPose();
  loop.startReturn(2.6, from, to);
  // The farther tip's way at 1.5 m/s: the stroke carried the tips about 2.5 m forward.
  const double way =
      std::max((to.leftPosition - from.leftPosition).norm(), (to.rightPosition - from.rightPosition).norm());
  EXPECT_GT(way, 2.0);
  EXPECT_NEAR(loop.returnSeconds(), way / PerformanceLoop::kReturnSpeed, 1e-9);
  // No jump: the path starts where the wands are and moves at most (peak speed 1.5 x the mean) x frame per frame.
  EXPECT_LT((loop.returnWands(2.6).leftPosition - from.leftPosition).norm(), 1e-6);
  const double peakStep = 1.5 * PerformanceLoop::kReturnSpeed * kFrame + 1e-4;  // smoothstep peaks at 1.5x its mean
  double t = 2.6;
  Vec3 last = from.leftPosition;
  const double bubbleGone = 4.5;  // the free bubble bursts meanwhile
  Action action = Action::Return;
  for (; action == Action::Return; t += kFrame) {
    action = loop.next(t, true, true, t >= bubbleGone ? bubbleGone : -1);
    const Vec3 now = loop.returnWands(t).leftPosition;
    EXPECT_LE((now - last).norm(), peakStep) << t;
    last = now;
  }
  t -= kFrame;
  // Back at the start pose, the new film is dipped once the stage was empty for autoDip (within a frame).
  EXPECT_EQ(action, Action::DipAndPlay);
  EXPECT_NEAR(t, std::max(bubbleGone + autoDip, 2.6 + loop.returnSeconds()), kFrame);
  EXPECT_LT((loop.returnWands(t).leftPosition - to.leftPosition).norm(), 1e-6);
  EXPECT_LT(loop.returnWands(t).leftVelocity.norm(), 1e-6);
  EXPECT_FALSE(loop.looping());
  EXPECT_EQ(loop.next(t + kFrame, false, false, -1), Action::Play);
}

TEST(PerformanceLoop, AnEmptyStageMidPerformanceStartsOverAfterTheAutoDip) {
  PerformanceLoop loop(0.5);
  EXPECT_EQ(loop.next(1.0, false, true, 0.8), Action::Play);  // burst by a key at 0.8 s: 0.2 s empty
  EXPECT_EQ(loop.next(1.3, false, true, 0.8), Action::StartReturn);
  loop.startReturn(1.3, startPose(), startPose());
  EXPECT_NEAR(loop.returnSeconds(), PerformanceLoop::kShortestReturn, 1e-12);  // no way to go: still a visible move
  EXPECT_EQ(loop.next(1.5, false, true, 0.8), Action::Return);
  EXPECT_EQ(loop.next(1.8, false, true, 0.8), Action::DipAndPlay);
}

TEST(PerformanceLoop, AFreeBubbleStillFlyingKeepsTheWandsWaitingAtTheStart) {
  PerformanceLoop loop(1.0);
  ASSERT_EQ(loop.next(2.6, true, true, -1), Action::StartReturn);
  loop.startReturn(2.6, endPose(), startPose());
  const double back = 2.6 + loop.returnSeconds();
  // The bubble flies on after the wands are back (the stage is not empty, the wands hold none): they wait.
  EXPECT_EQ(loop.next(back + 0.1, true, true, -1), Action::Return);
  EXPECT_EQ(loop.next(back + 3.0, true, true, -1), Action::Return);
  EXPECT_EQ(loop.next(back + 3.5, true, true, back + 3.2), Action::Return);  // gone 0.3 s ago
  EXPECT_EQ(loop.next(back + 4.2, true, true, back + 3.2), Action::DipAndPlay);
}

TEST(PerformanceLoop, AFilmDippedByHandDuringTheReturnIsBlownFromTheStart) {
  PerformanceLoop loop(2.0);
  ASSERT_EQ(loop.next(3.0, true, true, 2.9), Action::StartReturn);
  loop.startReturn(3.0, endPose(), startPose());
  EXPECT_EQ(loop.next(3.1, true, false, -1), Action::Return);  // D: a film on the returning wands rides along
  EXPECT_EQ(loop.next(3.0 + loop.returnSeconds(), true, false, -1), Action::StartPlaying);
}

TEST(PerformanceLoop, ANegativeAutoDipNeverLoops) {
  PerformanceLoop loop(-1.0);
  for (double t = 0; t < 100; t += 1.0) EXPECT_EQ(loop.next(t, true, true, 0.0), Action::Play);
}

}  // namespace
}  // namespace gb
