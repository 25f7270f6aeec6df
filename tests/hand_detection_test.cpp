#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "capture/hand_evaluation.h"
#include "capture/hand_finder.h"
#include "tests/synthetic_depth.h"

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
      if (accelerometer) o.segmentation.gravityUp = s.up;
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

// The hands the finder reports after a few frames of a still pose (the room and the performer settled).
HandSample handsOfPose(const test::BodyPose& pose, test::SceneOptions scene, test::SyntheticScene& last) {
  HandFinder finder;
  HandSample out;
  for (int i = 0; i < 3; ++i) {
    scene.seed = static_cast<unsigned>(i + 1);
    last = test::renderScene(pose, scene, i / 30.0);
    out = finder.update(last.frame);
  }
  return out;
}

// Both hands within 10 cm (the benchmark's criterion; measured 0.2-3.8 cm) in every pose of the synthetic
// benchmark but the crossing, at three tilts, with furniture, a wall 1 m behind the performer and Kinect noise.
// The forest never saw these capsule bodies: it learned real people.
TEST(HandDetection, FindsBothHandsInEveryPoseAtEveryTilt) {
  for (const std::string pose : {"forward", "arms-out", "together", "overhead", "one-arm-down"}) {
    for (const double pitch : {0.0, 10.0, 20.0}) {
      test::SceneOptions scene;
      scene.cameraPitch = pitch;
      scene.cameraHeight = test::cameraHeightFor(pitch, 2.6);
      scene.wallDistance = 3.6;
      test::SyntheticScene s;
      const HandSample out = handsOfPose(test::namedPose(pose), scene, s);
      ASSERT_TRUE(out.left.measured && out.right.measured) << pose << " at " << pitch;
      EXPECT_LT((out.left.position - s.leftHand).norm(), 0.10) << pose << " at " << pitch;
      EXPECT_LT((out.right.position - s.rightHand).norm(), 0.10) << pose << " at " << pitch;
      EXPECT_GT(std::min(out.left.confidence, out.right.confidence), 0.5) << pose << " at " << pitch;
    }
  }
}

// Arms held out sideways at the body's depth (nothing stands in front of the body), the camera tilted down 13
// degrees: each hand on its own side within 5 cm (measured 2-3 cm).
TEST(HandDetection, ArmsOutSidewaysAtBodyDepthAreFound) {
  test::SceneOptions scene;
  scene.cameraPitch = 13.0;
  scene.cameraHeight = test::cameraHeightFor(13.0, 2.6);
  test::SyntheticScene s;
  const HandSample out = handsOfPose(test::namedPose("arms-out"), scene, s);
  ASSERT_TRUE(out.left.measured && out.right.measured);
  EXPECT_LT((out.left.position - s.leftHand).norm(), 0.05);
  EXPECT_LT((out.right.position - s.rightHand).norm(), 0.05);
}

// The simple scene of the fakenect tests (level camera, no noise): both hands within 5 cm (measured 0.3-3 cm).
// The hand's centre is its front pushed back by what the real hands of the training data measured (4.7 cm);
// these hands are 5 cm spheres at the end of a capsule arm, shaped unlike a real hand.
TEST(HandDetection, FindsBothHandsOfTheSimpleSceneWithinFiveCentimetres) {
  const std::vector<std::pair<Vec3d, Vec3d>> poses = {
      {{0.25, 0.05, 2.0}, {-0.25, 0.0, 1.95}},   // both forward
      {{0.35, 0.3, 2.0}, {-0.15, -0.2, 2.15}},   // one high, one low and near the body
      {{0.09, 0.0, 1.95}, {-0.09, 0.02, 1.95}},  // close together, 18 cm apart
      {{0.55, -0.1, 2.2}, {-0.55, 0.25, 2.2}}};  // wide apart
  for (const auto& [left, right] : poses) {
    test::SyntheticPerformer performer;
    performer.leftHand = left;
    performer.rightHand = right;
    HandFinder finder;
    HandSample s;
    for (int i = 0; i < 3; ++i) s = finder.update(test::renderPerformer(performer, i / 30.0, static_cast<uint32_t>(i)));
    ASSERT_TRUE(s.left.measured && s.right.measured) << left.transpose() << " / " << right.transpose();
    EXPECT_LT((s.left.position - left).norm(), 0.05) << s.left.position.transpose() << " vs " << left.transpose();
    EXPECT_LT((s.right.position - right).norm(), 0.05) << s.right.position.transpose() << " vs " << right.transpose();
  }
}

// An arm hanging at the side: the hanging hand is found where it is (a real performer's idle hand hangs so),
// nothing on a leg or a foot; a room without a person has nobody in it.
TEST(HandDetection, TheHangingHandIsFoundAndNothingOnTheLegs) {
  test::SceneOptions scene;
  scene.cameraPitch = 13.0;
  scene.cameraHeight = test::cameraHeightFor(13.0, 2.6);
  test::SyntheticScene s;
  const HandSample out = handsOfPose(test::namedPose("one-arm-down"), scene, s);
  ASSERT_TRUE(out.left.measured && out.right.measured);
  EXPECT_LT((out.left.position - s.leftHand).norm(), 0.10);
  EXPECT_LT((out.right.position - s.rightHand).norm(), 0.10);

  test::BodyPose away;
  away.feet = Vec3d(0.0, 0.0, 9.0);  // beyond the band and the wall: an empty room with furniture
  const Detection empty = detectHands(test::renderScene(away, scene).frame, DetectionOptions{});
  EXPECT_EQ(empty.performerPixels, 0);
  EXPECT_TRUE(empty.hands.empty());

  kinect::DepthFrame nothing;  // no reading anywhere (lens covered, camera facing the sky)
  EXPECT_EQ(detectHands(nothing, DetectionOptions{}).performerPixels, 0);
}

// Hands crossing in front of the chest and back, twice, seen through the finder and scored as real depth is
// (hand_evaluation.h: found within 15 cm on its own side, false when near neither hand, swapped when near the
// other's): no frame swapped, at most 0.05 false hands per frame and at least 85% of the hands found (issue
// 32's targets; measured 99.6%, 0 and 0). While one hand passes behind the other the forest finds the hidden
// hand's visible forearm, 8-12 cm from it.
TEST(HandTracking, CrossingInFrontOfTheChestKeepsEachHandsIdentity) {
  test::SceneOptions scene;
  scene.cameraPitch = 10.0;
  scene.cameraHeight = test::cameraHeightFor(10.0, 2.5);
  HandFinder finder;
  HandScore score;
  for (int i = 0; i < 120; ++i) {
    const double t = i / 30.0;
    test::BodyPose pose = test::sequencePose("crossing", t);
    pose.feet.z() = 2.5;
    scene.seed = static_cast<unsigned>(i + 1);
    const test::SyntheticScene s = test::renderScene(pose, scene, t);
    HandSample truth;
    truth.time = t;
    truth.left = HandHold().update(t, s.leftHand);
    truth.right = HandHold().update(t, s.rightHand);
    scoreFrame(finder.update(s.frame), truth, score);
  }
  EXPECT_EQ(score.swappedFrames, 0);
  EXPECT_LE(score.falsePerFrame(), 0.05);
  EXPECT_GE(score.found15(), 0.85);
}

// Detections as the forest gives them: each with its side (+1 the forest's left hand, -1 its right hand).
Detection handsAt(std::initializer_list<std::pair<Vec3d, int>> hands, double confidence = 1.0) {
  Detection d;
  d.performerPixels = 20000;
  d.bodyDepth = 2.4;
  for (const auto& [p, side] : hands) d.hands.push_back({p, confidence, side, 1.0});
  return d;
}

// Each hand takes the strongest detection of its side, whatever the order and wherever it is (the forest tells
// the sides from the whole body: a hand crossed over to the other side is still its own); a mirrored image
// swaps the sides.
TEST(HandTracker, EachHandTakesItsOwnSidesDetection) {
  HandTracker tracker;
  for (int i = 0; i <= 30; ++i) {
    const double t = i / 30.0, x = 0.3 - 0.6 * t;  // the left hand sweeps across the right one
    Detection d = handsAt({{{x, 0.0, 1.7}, 1}, {{-x, 0.0, 2.0}, -1}});
    if (i % 2) std::swap(d.hands[0], d.hands[1]);  // the order carries no identity
    const HandSample s = tracker.update(t, d);
    ASSERT_TRUE(s.left.measured && s.right.measured);
    EXPECT_NEAR(s.left.position.x(), x, 1e-12) << t;
    EXPECT_NEAR(s.right.position.z(), 2.0, 1e-12) << t;
  }
  TrackerOptions mirrored;
  mirrored.mirrored = true;
  HandTracker other(mirrored);
  const HandSample m = other.update(0.0, handsAt({{{0.3, 0.0, 2.0}, 1}}));
  EXPECT_TRUE(m.right.measured);
  EXPECT_FALSE(m.left.seen());
}

// A hand not followed is taken only when the forest is sure (newConfidence); a followed hand also from a lower
// confidence near where it was going (followConfidence), but not when it jumps across the room.
TEST(HandTracker, AFollowedHandIsTakenFromLowerConfidenceOnlyNearItsPath) {
  TrackerOptions o;
  HandTracker tracker(o);
  const double unsure = 0.5 * (o.followConfidence + o.newConfidence);
  EXPECT_FALSE(tracker.update(0.0, handsAt({{{0.25, 0.0, 1.8}, 1}}, unsure)).left.measured);
  EXPECT_TRUE(tracker.update(1 / 30.0, handsAt({{{0.25, 0.0, 1.8}, 1}}, 1.0)).left.measured);
  EXPECT_TRUE(tracker.update(2 / 30.0, handsAt({{{0.27, 0.0, 1.8}, 1}}, unsure)).left.measured);
  const HandSample jump = tracker.update(3 / 30.0, handsAt({{{-0.6, 0.8, 1.8}, 1}}, unsure));
  EXPECT_FALSE(jump.left.measured);
  EXPECT_NEAR(jump.left.position.x(), 0.27, 1e-12);                                            // held where it was
  EXPECT_TRUE(tracker.update(4 / 30.0, handsAt({{{-0.6, 0.8, 1.8}, 1}}, 1.0)).left.measured);  // sure: it moved
}

TEST(HandTracker, HoldsALostHandWithDecayingConfidenceAndTakesItBack) {
  TrackerOptions o;
  HandTracker tracker(o);
  tracker.update(0.0, handsAt({{{0.25, 0.0, 1.8}, 1}, {{-0.25, 0.0, 1.8}, -1}}));
  // Occlusion: the right hand disappears for 0.5 s, then a frame goes missing altogether (no detection at all).
  double previous = 1.0;
  for (int i = 1; i <= 15; ++i) {
    const HandSample s = tracker.update(i / 30.0, handsAt({{{0.25, 0.0, 1.8}, 1}}));
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
  const HandSample back = tracker.update(17 / 30.0, handsAt({{{0.25, 0.0, 1.8}, 1}, {{-0.2, 0.05, 1.75}, -1}}));
  EXPECT_TRUE(back.left.measured && back.right.measured);
  EXPECT_EQ(back.right.position, Vec3d(-0.2, 0.05, 1.75));
}

// Close to the camera the forest's left hand may be followed onto a knee while the raised hand is found surely
// elsewhere. A followed detection outweighed letGoFrames in a row by a sure one of its side (letGoRatio times as
// confident) is let go for it; outweighed only now and then (noise), it is kept.
TEST(HandTracker, AFollowedHandTheDetectionsNoLongerSupportIsLetGo) {
  TrackerOptions o;
  HandTracker tracker(o);
  const Vec3d knee(0.2, -0.5, 1.3), raised(0.5, 0.3, 1.3);
  ASSERT_TRUE(tracker.update(0.0, handsAt({{knee, 1}}, 0.7)).left.measured);
  auto frame = [&](int i, double kneeConfidence) {
    Detection d = handsAt({{raised, 1}}, 0.9);
    d.hands.push_back({knee, kneeConfidence, 1, 1.0});
    return tracker.update(i / 30.0, d);
  };
  // Outweighed every other frame: the knee is kept.
  for (int i = 1; i <= 8; ++i) EXPECT_EQ(frame(i, i % 2 ? 0.35 : 0.6).left.position, knee) << i;
  // Outweighed frame after frame: kept for letGoFrames - 1 frames, then let go for the raised hand.
  for (int k = 1; k < o.letGoFrames; ++k) EXPECT_EQ(frame(8 + k, 0.35).left.position, knee) << k;
  const HandSample s = frame(8 + o.letGoFrames, 0.35);
  EXPECT_TRUE(s.left.measured);
  EXPECT_EQ(s.left.position, raised);
  EXPECT_EQ(frame(9 + o.letGoFrames, 0.35).left.position, raised);  // followed there from now on
}

// A hand mode on a limb that runs out of the image at its lower edge, in the image's lowest fifth, is a leg more
// often than a hand: its confidence is halved. The same mode on a limb that ends above the edge (a hanging hand), or
// higher up in the image, keeps its confidence.
TEST(HandDetection, AModeOnALimbLeavingTheImageAtItsLowerEdgeIsHalved) {
  const double z = 1.3;
  auto limb = [&](int fromRow, int toRow) {  // a vertical strip 6 grid pixels wide around column 200
    BodyDepth body;
    for (int v = fromRow; v < toRow; ++v)
      for (int u = 197; u <= 203; ++u) body.depth[static_cast<size_t>(v) * BodyDepth::kWidth + u] = float(z);
    return body;
  };
  const Vec3d low = kinect::pixelToCamera(400.0, 2.0 * 225.0, z);  // grid (200, 225): in the lowest fifth
  const Vec3d high = kinect::pixelToCamera(400.0, 2.0 * 120.0, z);
  EXPECT_EQ(lowerEdgeFactor(limb(100, BodyDepth::kHeight), low), kLimbAtEdgeFactor);  // a thigh out of the image
  EXPECT_EQ(lowerEdgeFactor(limb(100, 232), low), 1.0);                               // a hand hanging above the edge
  EXPECT_EQ(lowerEdgeFactor(limb(100, BodyDepth::kHeight), high), 1.0);  // a forearm well above the lowest fifth
  EXPECT_EQ(lowerEdgeFactor(BodyDepth{}, low), 1.0);                     // no body under it at all
}

}  // namespace
}  // namespace gb
