// The step and the render busy at once (app/outputs/step_render_overlap.h): lengths of joined intervals and of
// their intersection, exact (sums of the given endpoints).
#include "app/outputs/step_render_overlap.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace gb
