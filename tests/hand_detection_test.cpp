#include <gtest/gtest.h>

#include <cmath>

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

// Two hands at known places in a synthetic frame: each detected within 2 cm of its centre.
TEST(HandDetection, FindsBothHandsWithinTwoCentimetres) {
  const std::vector<std::pair<Vec3d, Vec3d>> poses = {
      {{0.25, 0.05, 1.9}, {-0.25, 0.0, 1.85}},    // both forward
      {{0.35, 0.3, 1.7}, {-0.15, -0.2, 2.1}},     // one high and far forward, one low and near the body
      {{0.08, 0.0, 1.8}, {-0.08, 0.02, 1.8}},     // close together, 16 cm apart
      {{0.45, -0.1, 1.6}, {-0.45, 0.25, 1.75}}};  // wide apart
  for (const auto& [left, right] : poses) {
    test::SyntheticPerformer performer;
    performer.leftHand = left;
    performer.rightHand = right;
    const Detection d = detectHands(test::renderPerformer(performer), DetectionOptions{});
    ASSERT_EQ(d.hands.size(), 2u) << left.transpose() << " / " << right.transpose();
    HandTracker tracker;
    const HandSample s = tracker.update(0.0, d);
    ASSERT_TRUE(s.left.measured && s.right.measured);
    EXPECT_LT((s.left.position - left).norm(), 0.02) << s.left.position.transpose() << " vs " << left.transpose();
    EXPECT_LT((s.right.position - right).norm(), 0.02) << s.right.position.transpose() << " vs " << right.transpose();
  }
}

TEST(HandDetection, AHandAtTheSideIsNotAHandAndNobodyIsNothing) {
  test::SyntheticPerformer performer;
  performer.rightHand.reset();
  const Detection one = detectHands(test::renderPerformer(performer), DetectionOptions{});
  ASSERT_EQ(one.hands.size(), 1u);
  EXPECT_LT((one.hands[0].position - *performer.leftHand).norm(), 0.02);

  performer.leftHand.reset();
  const Detection none = detectHands(test::renderPerformer(performer), DetectionOptions{});
  EXPECT_GT(none.performerPixels, 0);
  EXPECT_TRUE(none.hands.empty());

  kinect::DepthFrame empty;  // no reading anywhere (lens covered, camera facing the sky)
  EXPECT_EQ(detectHands(empty, DetectionOptions{}).performerPixels, 0);
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

TEST(HandTracker, FirstSightingTakesItsSideFromTheBodyOrTheOtherHand) {
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
}

}  // namespace
}  // namespace gb
