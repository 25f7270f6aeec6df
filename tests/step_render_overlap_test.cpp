// The step and the render busy at once (app/outputs/step_render_overlap.h): lengths of joined intervals and of
// their intersection, exact (sums of the given endpoints). The Vulkan stepper's step timed on the device:
// tests/renderer_test.cpp (AStepBehindAFrameIsTimedWhereTheDeviceRanIt).
#include "app/outputs/step_render_overlap.h"

#include <gtest/gtest.h>

#include "stages/cpu_stepper.h"

namespace gb {
namespace {

TEST(StepRenderOverlap, SharedTimeIsTheIntersectionOfTheJoinedIntervals) {
  StepRenderOverlap o;
  o.addStep(0.0, 1.0);
  o.addStep(2.0, 3.0);
  // Two frames drawn, the second before the first in the list and overlapping it: joined into 0.5..2.5.
  o.addRender({{1.5, 2.5}, {0.5, 1.6}});
  const StepRenderOverlap::Totals t = o.totals();
  EXPECT_DOUBLE_EQ(t.step, 2.0);
  EXPECT_DOUBLE_EQ(t.render, 2.0);
  EXPECT_DOUBLE_EQ(t.both, 1.0);  // 0.5..1.0 and 2.0..2.5
  EXPECT_TRUE(t.renderTimed);
}

TEST(StepRenderOverlap, WithoutTimedFramesNothingOverlapsAndTheRenderIsNotTimed) {
  StepRenderOverlap o;
  o.addStep(0.0, 1.0);
  o.addStep(1.0, 0.5);  // backwards: not a step
  const StepRenderOverlap::Totals t = o.totals();
  EXPECT_DOUBLE_EQ(t.step, 1.0);
  EXPECT_DOUBLE_EQ(t.both, 0.0);
  EXPECT_FALSE(t.renderTimed);
}

// A stepper with no device timestamps (the CPU's) is timed on the host, around its advance.
TEST(StepRenderOverlap, TheCpuStepperIsTimedOnTheHost) {
  StepRenderOverlap o;
  const CpuStepper cpu;
  o.addStep(cpu, 1.0, 1.25);
  o.addRender({{1.2, 2.0}});
  const StepRenderOverlap::Totals t = o.totals();
  EXPECT_DOUBLE_EQ(t.step, 0.25);
  EXPECT_NEAR(t.both, 0.05, 1e-12);  // 1.2..1.25, a difference of the given endpoints
}

}  // namespace
}  // namespace gb
