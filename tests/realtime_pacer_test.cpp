// The live loop's pacing (app/show/realtime_pacer.h): what it gives up, in which order, when the machine cannot keep
// up.
#include "app/show/realtime_pacer.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gb {
namespace {

TEST(RealTimePacer, FramesDueFollowTheWallClockAndTheLagBeyondTheCatchUpIsDropped) {
  using Clock = RealTimePacer::Clock;
  const Clock::time_point start{};
  RealTimePacer pacer({0.02, 10, 3, 4}, start);
  EXPECT_EQ(pacer.framesDue(start + std::chrono::milliseconds(10)), 0) << "half a frame: none due yet";
  EXPECT_EQ(pacer.framesDue(start + std::chrono::milliseconds(50)), 2);
  EXPECT_EQ(pacer.framesDue(start + std::chrono::milliseconds(250)), 4) << "10 more due, 4 caught up";
  EXPECT_EQ(pacer.droppedFrames(), 6);
}

TEST(RealTimePacer, TheImageShrinksFirstThenTheSweepsGoDownAndBothComeBack) {
  RealTimePacer pacer({0.02, 10, 3, 4, 0.5});
  constexpr int every = RealTimePacer::kRescaleEvery;
  // Every iteration simulates 2 frames (40 ms of wall time) and takes 100 ms: over budget.
  for (int k = 0; k < every; ++k) pacer.record(2, 50.0, 50.0);
  EXPECT_EQ(pacer.renderScale(), 0.75) << "the image gives way first";
  EXPECT_EQ(pacer.sweeps(), 10) << "the sweeps are kept while the image can shrink";
  for (int k = 0; k < every; ++k) pacer.record(2, 50.0, 50.0);
  EXPECT_EQ(pacer.renderScale(), 0.5);
  for (int k = 0; k < 7; ++k) pacer.record(2, 50.0, 50.0);
  EXPECT_EQ(pacer.sweeps(), 3) << "then one sweep fewer per iteration, down to the floor";
  for (int k = 0; k < 3 * every; ++k) pacer.record(2, 50.0, 50.0);
  EXPECT_EQ(pacer.renderScale(), 0.5) << "never below minRenderScale";
  EXPECT_EQ(pacer.sweeps(), 3) << "never below minSweeps";
  // Now each iteration takes 10 ms of its 40: the sweeps come back first, then the image, a step at a time.
  for (int k = 0; k < 7; ++k) pacer.record(2, 5.0, 5.0);
  EXPECT_EQ(pacer.sweeps(), 10);
  EXPECT_EQ(pacer.renderScale(), 0.5) << "the image waits for the sweeps";
  for (int k = 0; k < every; ++k) pacer.record(2, 5.0, 5.0);
  EXPECT_EQ(pacer.renderScale(), 0.75);
  for (int k = 0; k < every; ++k) pacer.record(2, 5.0, 5.0);
  EXPECT_EQ(pacer.renderScale(), 1.0);
  // A fixed image (minRenderScale 1, run --realtime): the sweeps give way at once.
  RealTimePacer fixed({0.02, 10, 3, 1});
  for (int k = 0; k < 7; ++k) fixed.record(1, 50.0, 50.0);
  EXPECT_EQ(fixed.sweeps(), 3);
  EXPECT_EQ(fixed.renderScale(), 1.0);
}

TEST(RealTimePacer, AWindowOfAnySizeComesDownToAnImageTheMachineDraws) {
  // 16384 x 16384: --min-render-scale 0.5 would still draw 8192 x 8192. The floor keeps at most 1280 x 720's pixels.
  const double floor = renderScaleFloor(0.5, 16384, 16384);
  EXPECT_NEAR(floor * floor * 16384.0 * 16384.0, 1280.0 * 720.0, 1.0);  // pixels; 1 pixel of rounding
  EXPECT_EQ(renderScaleFloor(0.5, 1280, 720), 0.5) << "a window of ordinary size keeps --min-render-scale";
  // 2 s to draw a frame, 4 frames (80 ms) due: after the first kRescaleEvery iterations it draws 0.2 of the width,
  // where 25 times fewer pixels take the frames' time, rather than a quarter step every ten frames of 2 s.
  RealTimePacer pacer({0.02, 10, 3, 4, floor});
  for (int k = 0; k < RealTimePacer::kRescaleEvery; ++k) pacer.record(4, 10.0, 2000.0);
  EXPECT_NEAR(pacer.renderScale(), std::sqrt(80.0 / 2010.0), 1e-12);  // exact arithmetic: one change
  for (int k = 0; k < 10 * RealTimePacer::kRescaleEvery; ++k) pacer.record(4, 10.0, 2000.0);
  EXPECT_EQ(pacer.renderScale(), floor) << "down to the floor, never below";
}

}  // namespace
}  // namespace gb
