// Who the performer is in rooms with walls, furniture, a floor and other people (performer_segmentation.h), on
// synthetic depth (synthetic_depth.h) where the truth is known exactly.
#include "capture/performer_segmentation.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/synthetic_depth.h"

namespace gb {
namespace {

test::SceneOptions roomAt(double pitch, double distance) {
  test::SceneOptions scene;
  scene.cameraPitch = pitch;
  scene.cameraHeight = test::cameraHeightFor(pitch, distance);
  scene.wallDistance = distance + 1.0;
  return scene;
}

// The performer taken is the person: their median point within 30 cm of the body's axis (the torso's front
// lies ~10 cm before it, the arms and legs around it).
void expectPerformerAt(const Segmentation& s, const Vec3d& feetInCamera, const std::string& where) {
  ASSERT_GE(s.performer, 0) << where << ": " << s.why;
  const BodyCandidate& p = s.candidates[static_cast<size_t>(s.performer)];
  EXPECT_NEAR(p.centre.x(), feetInCamera.x(), 0.3) << where << ": " << s.why;
  EXPECT_NEAR(p.depth, feetInCamera.z(), 0.4) << where << ": " << s.why;
}

// A camera's view of a scene point (scene space: floor y = 0, camera at (0, height, 0) pitched down).
Vec3d toCamera(const Vec3d& p, const test::SceneOptions& scene) {
  const double a = scene.cameraPitch * 3.14159265358979 / 180.0;
  const Vec3d d = p - Vec3d(0.0, scene.cameraHeight, 0.0);
  return {d.x(), d.y() * std::cos(a) + d.z() * std::sin(a), -d.y() * std::sin(a) + d.z() * std::cos(a)};
}

// From the first frame, with nothing learned: the person, not the wall behind (too large, flat), the chair or
// the table (too low), at the tilts a performer sets a camera to.
TEST(PerformerSegmentation, TakesThePersonNotTheWallOrTheFurnitureFromTheFirstFrame) {
  for (const double pitch : {0.0, 13.0, 20.0}) {
    const test::SceneOptions scene = roomAt(pitch, 2.6);
    const test::BodyPose pose = test::namedPose("arms-out");
    PerformerSegmenter segmenter;
    const Segmentation s = segmenter.segment(test::renderScene(pose, scene).frame);
    expectPerformerAt(s, toCamera(pose.feet + Vec3d(0, 1.0, 0), scene), "pitch " + std::to_string(pitch));
    EXPECT_GE(s.candidates.size(), 2u) << s.why;  // the furniture is seen, and passed over
  }
}

// 1.2 m from a camera tilted 13 degrees down: the head and the feet are out of view, the body is taller than
// the image and touches its top and bottom; it is still the performer, and the advice says so.
TEST(PerformerSegmentation, APerformerTooCloseToShowHeadAndFeetIsStillThePerformer) {
  test::SceneOptions scene = roomAt(13.0, 1.2);
  scene.cameraHeight = 1.3;
  test::BodyPose pose = test::namedPose("forward");
  pose.feet = Vec3d(0.0, 0.0, 1.3);
  PerformerSegmenter segmenter;
  const Segmentation s = segmenter.segment(test::renderScene(pose, scene).frame);
  expectPerformerAt(s, toCamera(pose.feet + Vec3d(0, 1.1, 0), scene), "at 1.2 m");
  const BodyCandidate& p = s.candidates[static_cast<size_t>(s.performer)];
  EXPECT_TRUE(p.cutAbove && p.cutBelow);
  EXPECT_NE(s.advice.find("step back"), std::string::npos) << s.advice;
}

// A second person half out of the view at its side edge, nearer than the performer: a passer-by, not the
// performer.
TEST(PerformerSegmentation, SomeoneAtTheEdgeOfTheViewIsNotThePerformer) {
  const test::SceneOptions scene = roomAt(10.0, 2.8);
  test::BodyPose performer = test::namedPose("forward");
  performer.feet = Vec3d(0.0, 0.0, 2.8);
  test::BodyPose passer = test::namedPose("one-arm-down");
  passer.feet = Vec3d(1.2, 0.0, 2.3);  // half out of the view
  kinect::DepthFrame frame = test::renderScene(performer, scene).frame;
  test::SceneOptions passerOnly = scene;
  passerOnly.furniture = false;
  const kinect::DepthFrame other = test::renderScene(passer, passerOnly).frame;
  for (size_t i = 0; i < frame.raw.size(); ++i) frame.raw[i] = std::min(frame.raw[i], other.raw[i]);  // nearer wins
  PerformerSegmenter segmenter;
  const Segmentation s = segmenter.segment(frame);
  expectPerformerAt(s, toCamera(performer.feet + Vec3d(0, 1.0, 0), scene), "with a passer-by");
}

// A room seen empty for a second is learned: nobody is taken while it is empty (a chair is not a person), and
// when the performer steps in, the furniture is no longer even a candidate.
TEST(PerformerSegmentation, LearnsTheEmptyRoomAndTakesThePerformerWhoStepsIn) {
  test::SceneOptions scene = roomAt(10.0, 2.6);
  const test::BodyPose pose = test::namedPose("forward");
  PerformerSegmenter segmenter;
  Segmentation s;
  scene.performer = false;  // the room alone
  for (int i = 0; i < 30; ++i) {
    scene.seed = static_cast<unsigned>(i + 1);
    s = segmenter.segment(test::renderScene(pose, scene, i / 30.0).frame);
    EXPECT_LT(s.performer, 0) << i << ": " << s.why;
  }
  EXPECT_GT(s.roomLearned, 0.8);
  scene.performer = true;
  scene.seed = 99;
  s = segmenter.segment(test::renderScene(pose, scene, 1.0).frame);
  expectPerformerAt(s, toCamera(pose.feet + Vec3d(0, 1.0, 0), scene), "after the room");
  EXPECT_EQ(s.candidates.size(), 1u) << s.why;
}

// A body taken for the performer that never moves for more than ten seconds is part of the room (a coat on a
// stand): it is learned, and then nobody is taken.
TEST(PerformerSegmentation, ABodyThatNeverMovesBecomesTheRoom) {
  const test::SceneOptions scene = roomAt(10.0, 2.6);
  const kinect::DepthFrame still = test::renderScene(test::namedPose("forward"), scene).frame;
  PerformerSegmenter segmenter;
  ASSERT_GE(segmenter.segment(still).performer, 0);
  Segmentation s;
  for (int i = 0; i < 330; ++i) s = segmenter.segment(still);  // 11 s
  EXPECT_LT(s.performer, 0) << s.why;
}

// Nobody: an empty band and a covered lens say so and what to do.
TEST(PerformerSegmentation, NobodyIsNothingAndSaysWhatToDo) {
  kinect::DepthFrame nothing;  // no reading anywhere (lens covered, camera facing the sky)
  PerformerSegmenter segmenter;
  const Segmentation s = segmenter.segment(nothing);
  EXPECT_LT(s.performer, 0);
  EXPECT_NE(s.why.find("no body in the depth band"), std::string::npos) << s.why;
  EXPECT_FALSE(s.advice.empty());
}

}  // namespace
}  // namespace gb
