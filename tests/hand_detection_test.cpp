#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hand_detector.h"
#include "synthetic_depth.h"

namespace gb {
namespace {

TEST(KinectDepth, RawDisparityAndMetresInvertEachOtherWithinOneRawStep) {
  EXPECT_EQ(kinect::rawToMetres(kinect::kNoReading), 0.0);
  EXPECT_EQ(kinect::metresToRaw(0.1), kinect::kNoReading);   // nearer than the Kinect sees
  EXPECT_EQ(kinect::metresToRaw(20.0), kinect::kNoReading);  // beyond the fit
  // Magnenat's fit at one raw value, computed by hand: 0.1236 tan(900 / 2842.5 + 1.1863) = 1.8182 m.
  EXPECT_NEAR(kinect::rawToMetres(900), 1.8182, 5e-4);
  for (double z = 0.6; z < 4.0; z += 0.1) {
    const uint16_t raw = kinect::metresToRaw(z);
    const double step = kinect::rawToMetres(raw + 1) - kinect::rawToMetres(raw);
    EXPECT_NEAR(kinect::rawToMetres(raw), z, 0.5 * step + 1e-9) << z;
    EXPECT_FLOAT_EQ(kinect::depthTable()[raw], static_cast<float>(kinect::rawToMetres(raw)));
  }
}

TEST(KinectDepth, PixelsAndCameraSpaceRoundTripWithYUp) {
  const Vec3d centre = kinect::pixelToCamera(kinect::kCx, kinect::kCy, 2.0);
  EXPECT_NEAR(centre.norm(), 2.0, 1e-12);
  EXPECT_GT(kinect::pixelToCamera(kinect::kCx, 10, 2.0).y(), 0.0);   // the top of the image is up
  EXPECT_GT(kinect::pixelToCamera(600, kinect::kCy, 2.0).x(), 0.0);  // its right is +x
  const Vec3d p(0.3, -0.2, 1.7);
  const Eigen::Vector2d px = kinect::cameraToPixel(p);
  EXPECT_LT((kinect::pixelToCamera(px.x(), px.y(), p.z()) - p).norm(), 1e-12);
}

// The floor of a tilted camera, found with and without the accelerometer: within 1 degree and 3 cm, the floor
// being a plane fitted to thousands of points with 1-4 cm of Kinect noise and quantisation. (A level camera at
// chest height sees only a sliver of floor in front of the wall: docs/capture.md.)
TEST(FloorRemoval, FindsTheFloorOfACameraTiltedUpToTwentyDegrees) {
  for (const double pitch : {5.0, 13.0, 20.0}) {
    test::SceneOptions scene;
    scene.cameraPitch = pitch;
    scene.cameraHeight = test::cameraHeightFor(pitch, 2.5);
    const test::SyntheticScene s = test::renderScene(test::namedPose("forward"), scene);
    for (const bool accelerometer : {false, true}) {
      DetectionOptions o;
      if (accelerometer) o.gravityUp = s.up;
      const Detection d = detectHands(s.frame, o);
      ASSERT_TRUE(d.floor) << pitch;
      EXPECT_LT(std::acos(std::min(1.0, d.floor->up.dot(s.up))) * 180.0 / 3.14159265, 1.0) << pitch;
      // The camera's height over it: the fitted plane within 3 cm; along a measured gravity the floor points'
      // mean height, within 1 cm (the middle of the densest layer alone is only good to a 3 cm bin).
      EXPECT_NEAR(-d.floor->offset, s.floorDistance, accelerometer ? 0.01 : 0.03) << pitch;
      // Nothing on the floor is taken for a hand, and the feet are not hands either.
      for (const DetectedHand& h : d.hands) EXPECT_GT(d.floor->heightOf(h.position), 0.5) << pitch;
    }
  }
}

// Both hands within 10 cm (the benchmark's criterion; typical errors are 1-3 cm) in every pose of the benchmark
// but the crossing, at three tilts, with furniture, a wall 1 m behind the performer and Kinect noise.
TEST(HandDetection, FindsBothHandsInEveryPoseAtEveryTilt) {
  for (const std::string pose : {"forward", "arms-out", "together", "overhead"}) {
    for (const double pitch : {0.0, 10.0, 20.0}) {
      test::SceneOptions scene;
      scene.cameraPitch = pitch;
      scene.cameraHeight = test::cameraHeightFor(pitch, 2.6);
      scene.wallDistance = 3.6;
      const test::SyntheticScene s = test::renderScene(test::namedPose(pose), scene);
      const Detection d = detectHands(s.frame, DetectionOptions{});
      ASSERT_EQ(d.hands.size(), 2u) << pose << " at " << pitch;
      HandTracker tracker;
      const HandSample out = tracker.update(0.0, d);
      ASSERT_TRUE(out.left.measured && out.right.measured) << pose << " at " << pitch;
      EXPECT_LT((out.left.position - s.leftHand).norm(), 0.10) << pose << " at " << pitch;
      EXPECT_LT((out.right.position - s.rightHand).norm(), 0.10) << pose << " at " << pitch;
      EXPECT_GT(out.left.confidence, 0.5) << pose << " at " << pitch;
    }
  }
}

// Arms held out sideways at the body's depth: nothing stands in front of the body, which defeated the old
// nearest-extremity detector; the geodesic extrema find them, on their own sides, within 5 cm.
TEST(HandDetection, ArmsOutSidewaysAtBodyDepthAreFound) {
  test::SceneOptions scene;
  scene.cameraPitch = 13.0;  // the tilt of the recording in issue 15
  scene.cameraHeight = test::cameraHeightFor(13.0, 2.6);
  const test::SyntheticScene s = test::renderScene(test::namedPose("arms-out"), scene);
  const Detection d = detectHands(s.frame, DetectionOptions{});
  ASSERT_EQ(d.hands.size(), 2u);
  for (const DetectedHand& h : d.hands) {
    const bool left = h.position.x() > 0.0;
    EXPECT_LT((h.position - (left ? s.leftHand : s.rightHand)).norm(), 0.05);
    EXPECT_EQ(h.side, left ? 1 : -1);
    EXPECT_GT(h.sideConfidence, 0.9);
  }
  ASSERT_TRUE(d.head);
  EXPECT_NEAR(d.head->x(), 0.0, 0.1);
}

// The simple scene of the fakenect tests (level camera, no noise): both hands within 3 cm (the visible cap's
// centroid pushed back 2 cm lands within a centimetre or two of a 5 cm sphere's centre).
TEST(HandDetection, FindsBothHandsOfTheSimpleSceneWithinThreeCentimetres) {
  const std::vector<std::pair<Vec3d, Vec3d>> poses = {
      {{0.25, 0.05, 2.0}, {-0.25, 0.0, 1.95}},   // both forward
      {{0.35, 0.3, 2.0}, {-0.15, -0.2, 2.15}},   // one high, one low and near the body
      {{0.09, 0.0, 1.95}, {-0.09, 0.02, 1.95}},  // close together, 18 cm apart
      {{0.55, -0.1, 2.2}, {-0.55, 0.25, 2.2}}};  // wide apart
  for (const auto& [left, right] : poses) {
    test::SyntheticPerformer performer;
    performer.leftHand = left;
    performer.rightHand = right;
    const Detection d = detectHands(test::renderPerformer(performer), DetectionOptions{});
    ASSERT_EQ(d.hands.size(), 2u) << left.transpose() << " / " << right.transpose();
    HandTracker tracker;
    const HandSample s = tracker.update(0.0, d);
    ASSERT_TRUE(s.left.measured && s.right.measured);
    EXPECT_LT((s.left.position - left).norm(), 0.03) << s.left.position.transpose() << " vs " << left.transpose();
    EXPECT_LT((s.right.position - right).norm(), 0.03) << s.right.position.transpose() << " vs " << right.transpose();
  }
}

// An arm hanging at the side, the knees and the feet are not hands; a room without a person has nobody in it.
TEST(HandDetection, NoFalseHandOnTheLegsAndNobodyIsNothing) {
  test::SceneOptions scene;
  scene.cameraPitch = 13.0;
  scene.cameraHeight = test::cameraHeightFor(13.0, 2.6);
  const test::SyntheticScene s = test::renderScene(test::namedPose("one-arm-down"), scene);
  const Detection one = detectHands(s.frame, DetectionOptions{});
  ASSERT_GE(one.hands.size(), 1u);
  for (const DetectedHand& h : one.hands) {
    // Either the raised left hand or the hanging right one where it is: nothing on a leg.
    const double nearest = std::min((h.position - s.leftHand).norm(), (h.position - s.rightHand).norm());
    EXPECT_LT(nearest, 0.10) << h.position.transpose();
  }

  test::BodyPose away;
  away.feet = Vec3d(0.0, 0.0, 9.0);  // beyond the band and the wall: an empty room with furniture
  const Detection empty = detectHands(test::renderScene(away, scene).frame, DetectionOptions{});
  EXPECT_EQ(empty.performerPixels, 0);
  EXPECT_TRUE(empty.hands.empty());

  kinect::DepthFrame nothing;  // no reading anywhere (lens covered, camera facing the sky)
  EXPECT_EQ(detectHands(nothing, DetectionOptions{}).performerPixels, 0);
}

// Hands crossing in front of the chest and back, twice, seen through the detector and the tracker: a reported
// hand is never the other one (0 swaps: issue 15's target), at most 2% of the frames report a hand more than
// 10 cm from its own (the benchmark's false-hand target), and occlusion while the hands pass costs some
// frames (at least 70% of the hands are found here; gb_depth_bench measures all motions together).
TEST(HandTracking, CrossingInFrontOfTheChestKeepsEachHandsIdentity) {
  test::SceneOptions scene;
  scene.cameraPitch = 10.0;
  scene.cameraHeight = test::cameraHeightFor(10.0, 2.5);
  HandTracker tracker;
  int found = 0, expected = 0, falseHands = 0, swapped = 0;
  constexpr int kFrames = 120;
  for (int i = 0; i < kFrames; ++i) {
    const double t = i / 30.0;
    test::BodyPose pose = test::sequencePose("crossing", t);
    pose.feet.z() = 2.5;
    scene.seed = static_cast<unsigned>(i + 1);
    const test::SyntheticScene s = test::renderScene(pose, scene, t);
    const HandSample out = tracker.update(t, detectHands(s.frame, DetectionOptions{}));
    const Vec3d truth[2] = {s.leftHand, s.rightHand};
    for (int h = 0; h < 2; ++h) {
      const HandObservation& o = out.hand(h == 0 ? Hand::Left : Hand::Right);
      ++expected;
      if (!o.measured) continue;
      const bool own = (o.position - truth[h]).norm() < 0.10;
      found += own;
      falseHands += !own;
      swapped += !own && (o.position - truth[1 - h]).norm() < 0.10;
    }
  }
  EXPECT_EQ(swapped, 0);
  EXPECT_LE(falseHands, 0.02 * kFrames);
  EXPECT_GE(found, 0.7 * expected);
}

Detection handsAt(std::initializer_list<Vec3d> points) {
  Detection d;
  d.performerPixels = 20000;
  d.bodyDepth = 2.4;
  for (const Vec3d& p : points) d.hands.push_back({p, 500});
  return d;
}

TEST(HandTracker, KeepsIdentityWhenTheHandsCrossAndNeverJumps) {
  HandTracker tracker;
  // The left hand (camera +x) sweeps to the right in front of the right hand sweeping to the left.
  for (int i = 0; i <= 30; ++i) {
    const double t = i / 30.0, x = 0.3 - 0.6 * t;
    Detection d = handsAt({{x, 0.0, 1.7}, {-x, 0.0, 2.0}});
    if (i % 2) std::swap(d.hands[0], d.hands[1]);  // detection order carries no identity
    const HandSample s = tracker.update(t, d);
    ASSERT_TRUE(s.left.measured && s.right.measured);
    EXPECT_NEAR(s.left.position.x(), x, 1e-12) << t;
    EXPECT_NEAR(s.right.position.z(), 2.0, 1e-12) << t;
  }
  // A detection across the room the next frame is not the left hand: it is held where it was.
  const HandSample jump = tracker.update(1.0 + 1.0 / 30, handsAt({{1.5, 0.0, 1.0}, {0.3, 0.0, 2.0}}));
  EXPECT_FALSE(jump.left.measured);
  EXPECT_NEAR(jump.left.position.x(), -0.3, 1e-12);
  EXPECT_TRUE(jump.right.measured);
}

TEST(HandTracker, HoldsALostHandWithDecayingConfidenceAndTakesItBackNearby) {
  TrackerOptions o;
  HandTracker tracker(o);
  tracker.update(0.0, handsAt({{0.25, 0.0, 1.8}, {-0.25, 0.0, 1.8}}));
  // Occlusion: the right hand disappears for 0.5 s, then a frame goes missing altogether (no detection at all).
  double previous = 1.0;
  for (int i = 1; i <= 15; ++i) {
    const HandSample s = tracker.update(i / 30.0, handsAt({{0.25, 0.0, 1.8}}));
    EXPECT_TRUE(s.left.measured);
    EXPECT_FALSE(s.right.measured);
    EXPECT_EQ(s.right.position, Vec3d(-0.25, 0.0, 1.8));
    EXPECT_LT(s.right.confidence, previous);
    previous = s.right.confidence;
  }
  EXPECT_NEAR(previous, std::exp(-0.5 / o.holdTime), 1e-12);
  const HandSample both = tracker.update(16 / 30.0, Detection{});
  EXPECT_FALSE(both.left.measured || both.right.measured);
  EXPECT_TRUE(both.left.seen() && both.right.seen());
  const HandSample back = tracker.update(17 / 30.0, handsAt({{0.25, 0.0, 1.8}, {-0.2, 0.05, 1.75}}));
  EXPECT_TRUE(back.left.measured && back.right.measured);
  EXPECT_EQ(back.right.position, Vec3d(-0.2, 0.05, 1.75));
}

// A hand seen before keeps a detection near it: a never-seen hand's first sighting costs something, so it
// cannot take the detection (issue 15: wands swapped sides mid-take), and it must lie on its own side.
TEST(HandTracker, ANeverSeenHandDoesNotStealTheOtherHandsDetection) {
  HandTracker tracker;
  Detection first = handsAt({{0.2, 0.0, 1.8}});
  first.bodyCentreX = 0.0;
  ASSERT_TRUE(tracker.update(0.0, first).left.measured);
  for (int i = 1; i <= 10; ++i) {
    // The left hand drifts across the body's middle; the right one is never seen.
    Detection d = handsAt({{0.2 - 0.04 * i, 0.0, 1.8}});
    d.bodyCentreX = 0.0;
    const HandSample s = tracker.update(i / 30.0, d);
    EXPECT_TRUE(s.left.measured) << i;
    EXPECT_FALSE(s.right.seen()) << i;
  }
}

TEST(HandTracker, FirstSightingTakesItsSideFromTheArmOrTheBody) {
  HandTracker tracker;
  Detection d = handsAt({{-0.2, 0.0, 1.8}});
  d.bodyCentreX = 0.0;
  const HandSample s = tracker.update(0.0, d);
  EXPECT_TRUE(s.right.measured);  // camera -x: the performer's right
  EXPECT_FALSE(s.left.seen());
  EXPECT_EQ(s.left.confidence, 0.0);
  TrackerOptions mirrored;
  mirrored.mirrored = true;
  HandTracker other(mirrored);
  EXPECT_TRUE(other.update(0.0, d).left.measured);
  // The arm's side, when the detector is sure of it, outweighs where the hand is (a hand crossed over).
  d.hands[0].side = 1;
  d.hands[0].sideConfidence = 1.0;
  HandTracker crossed;
  EXPECT_TRUE(crossed.update(0.0, d).left.measured);
}

}  // namespace
}  // namespace gb
