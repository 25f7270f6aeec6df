// The performer's touch judged on real Kinect v1 depth (../shared/real-depth/utd-mhad): a still bubble placed by a
// recording's ground truth, the body found in its depth as the collider. `giantbubble evaluate --touch` runs every
// recording of the judged actions (docs/capture.md); this runs one of each kind.
#include <gtest/gtest.h>

#include "app/commands/film_evaluation.h"
#include "scene/scene_file.h"
#include "tests/real_depth.h"

namespace gb {
namespace {

FilmEvaluationOptions defaultScene() {
  return {resolveScene("default").run, DetectionOptions{}, TrackerOptions{}, false};
}

TEST(TouchOnRealDepth, APushBurstsTheBubbleAtItsFarthestReachAsTheHandEntersIt) {
  REQUIRE_REAL_DEPTH(recording, "a18_s1_t1");  // a two-hand push
  const TouchTrial trial = playTouchOnRecording(*recording, defaultScene());
  ASSERT_TRUE(trial.touchBurst) << "the push never burst it (burst first by: " << trial.otherBurst << ")";
  // The window: from 0.3 s before the true hand (the Kinect skeleton's joint) enters the bubble, as the hand's
  // front surface leads the joint, to 0.2 s after.
  EXPECT_TRUE(trial.passed()) << "burst at " << *trial.touchBurst << " s, the hand entered at " << trial.entry << " s";
}

TEST(TouchOnRealDepth, AWaveLeavesABubbleHalfAMetreFromItsHandsWhole) {
  REQUIRE_REAL_DEPTH(recording, "a3_s1_t1");  // a right-hand wave
  const TouchTrial trial = playTouchOnRecording(*recording, defaultScene());
  EXPECT_FALSE(trial.touchBurst) << "burst by a touch at " << trial.touchBurst.value_or(0) << " s";
  EXPECT_TRUE(trial.otherBurst.empty()) << "burst by " << trial.otherBurst;
}

}  // namespace
}  // namespace gb
