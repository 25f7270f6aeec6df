#include "capture/wand_input.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <functional>
#include <future>
#include <mutex>
#include <numbers>
#include <thread>

#include "capture/hand_sources.h"
#include "capture/threaded_hand_source.h"
#include "capture/trajectory_metrics.h"

namespace gb {
namespace {

// A source from a function of time, that ends or fails after a number of samples.
class FunctionSource : public HandSource {
 public:
  FunctionSource(std::function<HandSample(double)> f, int samples, bool fails)
      : f_(std::move(f)), samples_(samples), fails_(fails) {}
  std::optional<HandSample> next() override {
    if (index_ == samples_) {
      if (fails_) throw HandSourceLost("the Kinect stopped responding (unplugged?)");
      return std::nullopt;
    }
    return f_(10.0 + index_++ / 30.0);  // source times need not start at 0
  }
  [[nodiscard]] std::string describe() const override { return "function"; }

 private:
  std::function<HandSample(double)> f_;
  int samples_, index_ = 0;
  bool fails_;
};

HandSample moving(double t) {
  HandSample s;
  s.time = t;
  s.left.position = Vec3d(0.25 + 0.3 * (t - 10.0), 0.0, 2.0);
  s.right.position = Vec3d(-0.25, 0.1 * (t - 10.0), 2.0);
  for (HandObservation* h : {&s.left, &s.right}) {
    h->measured = true;
    h->confidence = 1.0;
  }
  return s;
}

bool mentions(const std::vector<std::string>& messages, const std::string& text) {
  for (const std::string& m : messages)
    if (m.find(text) != std::string::npos) return true;
  return false;
}

TEST(Calibration, MapsTheCameraToTheWorldAndBack) {
  Calibration c;
  EXPECT_LT((c.toWorld(c.performer) - c.anchor).norm(), 1e-12);
  // The performer's left hand is on the camera's +x side; it becomes the left wand at world -x.
  EXPECT_LT(c.toWorld(c.performer + Vec3d(0.25, 0, 0)).x(), c.anchor.x());
  // A push towards the camera is a stroke towards world +z, scaled by the reach; up stays up.
  EXPECT_NEAR(c.toWorld(c.performer + Vec3d(0, 0, -0.5)).z() - c.anchor.z(), 0.5 * c.reach, 1e-12);
  EXPECT_NEAR(c.toWorld(c.performer + Vec3d(0, 0.1, 0)).y() - c.anchor.y(), 0.1 * c.reach, 1e-12);
  EXPECT_NEAR((c.restHand(Hand::Left) - c.restHand(Hand::Right)).norm(), c.restSeparation / c.reach, 1e-12);
  EXPECT_LT(c.toWorld(c.restHand(Hand::Left)).x(), 0.0);
  // A camera pitched up sees a level point below its axis; the calibration puts it back level.
  c.cameraPitch = 20.0;
  const double a = 20.0 * std::numbers::pi / 180.0;
  const Vec3d ahead = c.performer + Vec3d(0.0, -std::sin(a), std::cos(a)) * 0.4;  // 0.4 m further away, level
  EXPECT_NEAR(c.toWorld(ahead).y(), c.toWorld(c.performer).y(), 1e-12);
  const Vec3d p(0.1, 0.2, 1.7);
  EXPECT_LT((c.toCamera(c.toWorld(p)) - p).norm(), 1e-12);
  EXPECT_LT((c.velocityToWorld(p) - (c.toWorld(p) - c.toWorld(Vec3d::Zero()))).norm(), 1e-12);
}

TEST(WandInput, AScriptThroughTheStabilizerFollowsTheScriptedWandsInTheWorld) {
  const GestureOptions g;
  ScriptedWands exact(Gesture::Circles, g);
  StabilizedWands stabilized(std::make_unique<ScriptedHandSource>(Gesture::Circles, g, Calibration{}),
                             StabilizerOptions{}, Calibration{});
  const double lagTime = 0.1;                 // the B-spline's three samples at 30 Hz
  for (double t = 0.0; t < 4.0; t += 0.02) {  // the simulation's frames, 50 Hz
    const WandFrame f = stabilized.at(t);
    const WandState truth = exact.at(std::max(0.0, t - lagTime)).wands;
    EXPECT_LT((f.wands.leftPosition - truth.leftPosition).norm(), 0.03) << t;
    EXPECT_LT((f.wands.rightPosition - truth.rightPosition).norm(), 0.03) << t;
  }
  EXPECT_TRUE(stabilized.takeMessages().empty());
}

TEST(WandInput, ALostCameraMidPerformanceWarnsAndTheWandsHoldStill) {
  StabilizedWands input(std::make_unique<FunctionSource>(moving, 30, true), StabilizerOptions{}, Calibration{});
  for (double t = 0.0; t < 0.9; t += 0.02) input.at(t);
  EXPECT_TRUE(input.takeMessages().empty());
  std::vector<std::string> messages;
  WandFrame previous = input.at(0.9);
  double largestStep = 0.0;
  for (double t = 0.92; t < 3.0; t += 0.02) {
    const WandFrame f = input.at(t);
    for (const std::string& m : input.takeMessages()) messages.push_back(m);
    largestStep = std::max(largestStep, double((f.wands.leftPosition - previous.wands.leftPosition).norm()));
    previous = f;
  }
  EXPECT_TRUE(mentions(messages, "warning: input lost at t = 0.9")) << (messages.empty() ? "" : messages[0]);
  EXPECT_TRUE(mentions(messages, "unplugged"));
  EXPECT_TRUE(mentions(messages, "the wands hold still"));
  EXPECT_LT(largestStep, 0.3 * 2.0 * 0.02 + 1e-4);  // never faster than the hand moved (world: reach 2)
  EXPECT_LT(previous.wands.leftVelocity.norm(), 1e-4);
  const WandFrame last = input.at(3.5);
  EXPECT_LT((last.wands.leftPosition - previous.wands.leftPosition).norm(), 1e-5);
  EXPECT_FALSE(std::isfinite(last.leftHand.x()));  // no measured input any more
}

TEST(WandInput, AHandNotSeenIsReportedHeldAndReportedAgainWhenItComesBack) {
  auto blinking = [](double t) {
    HandSample s = moving(t);
    if (t > 10.31 && t < 10.8) {
      s.right.measured = false;
      s.right.confidence = 0.5;
    }
    return s;
  };
  StabilizedWands input(std::make_unique<FunctionSource>(blinking, 60, false), StabilizerOptions{}, Calibration{});
  std::vector<std::string> messages;
  for (double t = 0.0; t < 2.5; t += 0.02) {
    input.at(t);
    for (const std::string& m : input.takeMessages()) messages.push_back(m);
  }
  EXPECT_TRUE(mentions(messages, "warning: right hand not seen since t = 0.30 s"));
  EXPECT_TRUE(mentions(messages, "note: right hand seen again"));
  EXPECT_TRUE(mentions(messages, "note: input ended at t = 1.97 s"));  // and no more about hands after that
  EXPECT_FALSE(mentions(messages, "left hand"));
}

TEST(WandInput, AGapInTheInputIsRestedThroughNotJumpedOver) {
  auto gappy = [](double t) {
    HandSample s = moving(t < 10.5 ? t : t + 1.0);  // one second missing after 0.5 s
    return s;
  };
  StabilizedWands input(std::make_unique<FunctionSource>(gappy, 45, false), StabilizerOptions{}, Calibration{});
  Vec3 previous = input.at(0.0).wands.leftPosition;
  double largestStep = 0.0;
  for (double t = 0.02; t < 3.0; t += 0.02) {
    const Vec3 p = input.at(t).wands.leftPosition;
    largestStep = std::max(largestStep, double((p - previous).norm()));
    previous = p;
  }
  EXPECT_LT(largestStep, StabilizerOptions{}.maxSpeed * 2.0 * 0.02 + 1e-4);
}

TEST(WandInput, AutomaticCalibrationCentresThePerformerBetweenTheHands) {
  Calibration c;
  c.autoPerformer = true;
  auto offCentre = [](double t) {
    HandSample s = moving(t);
    s.left.position += Vec3d(1.0, 0.2, 0.5);
    s.right.position += Vec3d(1.0, 0.2, 0.5);
    if (t < 10.19) s.right.measured = false;  // the right hand shows up a little later
    return s;
  };
  StabilizedWands input(std::make_unique<FunctionSource>(offCentre, 30, false), StabilizerOptions{}, c);
  const auto messages = input.takeMessages();
  EXPECT_TRUE(mentions(messages, "calibration: performer at (1.03, 0.21, 2.50) m")) << messages.front();
  EXPECT_NEAR(input.calibration().performer.x(), 1.0 + 0.5 * 0.3 * 0.2, 1e-3);
}

// The film is made on the performer's hands. Nobody for 1.2 s, then the left hand alone, raised far
// out to the side, for 1.2 s, then both hands at rest: run time 0 is the first sample with both hands, the
// wands start on them (the rest pose, tips 1 m apart), and the wait is said once per second of input.
TEST(WandInput, APerformerFoundLateStartsTheWandsOnBothHandsAndTheWaitIsSaid) {
  const Vec3d performer(0.1, -0.1, 2.3);
  auto late = [&](double t) {
    HandSample s;
    s.time = t;
    const double since = t - 10.0;
    s.left.position = since < 2.4 ? Vec3d(performer + Vec3d(0.7, 0.6, -0.3)) : Vec3d(performer + Vec3d(0.25, 0, 0));
    s.right.position = performer - Vec3d(0.25, 0, 0);
    s.left.measured = since >= 1.2;
    s.right.measured = since >= 2.4;
    for (HandObservation* h : {&s.left, &s.right}) {
      h->confidence = h->measured ? 1.0 : 0.0;
      if (!h->measured) h->position = Vec3d::Constant(NAN);
    }
    return s;
  };
  Calibration c;
  c.autoPerformer = true;
  std::vector<std::string> said;
  std::vector<HandSample> samples;
  for (int i = 0; i < 150; ++i) samples.push_back(late(10.0 + i / 30.0));
  PerformerWait wait;
  wait.enabled = true;
  wait.say = [&](const std::string& m) { said.push_back(m); };
  StabilizedWands input(std::make_unique<ReplayHandSource>(samples, "late"), StabilizerOptions{}, c, wait);
  // Found at the first sample at or after 2.4 s: sample 72 at 30 Hz (2.4 s; within one sample of it).
  ASSERT_TRUE(input.performerFound());
  EXPECT_NEAR(*input.performerFound(), 2.4, 1.0 / 30.0 + 1e-9);
  // Once per second of input while waiting: at 0, 1 and 2 s (three messages, not one per sample).
  ASSERT_EQ(said.size(), 3u);
  EXPECT_EQ(said[0], "waiting for a performer: no hands in the input (0.00 s of input)");
  EXPECT_TRUE(said[2].find("the left hand found, waiting for the other") != std::string::npos) << said[2];
  const auto messages = input.takeMessages();
  EXPECT_TRUE(mentions(messages, "note: performer found after 2.40 s of input")) << messages.front();
  EXPECT_TRUE(mentions(messages, "calibration: performer at (0.10, -0.10, 2.30) m"));
  // The wands start where the hands are: the rest pose, 1 mm (float world coordinates) at most from it.
  const WandFrame first = input.at(0.0);
  const Calibration& calibrated = input.calibration();
  EXPECT_LT((first.wands.leftPosition.cast<double>() - calibrated.toWorld(calibrated.restHand(Hand::Left))).norm(),
            1e-3);
  EXPECT_LT((first.wands.rightPosition.cast<double>() - calibrated.toWorld(calibrated.restHand(Hand::Right))).norm(),
            1e-3);
  // The run lasts what is left of the input after the wait (149 intervals minus the 72 waited through).
  ASSERT_TRUE(input.length());
  EXPECT_NEAR(*input.length(), 149.0 / 30.0 - *input.performerFound(), 1e-9);
}

// Without both hands ever, the run starts where the input does, with a warning (not a hang, not an error).
TEST(WandInput, AnInputThatNeverShowsBothHandsStartsWhereItDoesWithAWarning) {
  auto oneHand = [](double t) {
    HandSample s = moving(t);
    s.right.measured = false;
    s.right.position = Vec3d::Constant(NAN);
    return s;
  };
  std::vector<std::string> said;
  PerformerWait wait;
  wait.enabled = true;
  wait.say = [&](const std::string& m) { said.push_back(m); };
  StabilizedWands input(std::make_unique<FunctionSource>(oneHand, 45, false), StabilizerOptions{}, Calibration{}, wait);
  EXPECT_FALSE(input.performerFound());
  EXPECT_EQ(said.size(), 2u);  // at 0 and 1 s of the 1.5 s input
  EXPECT_TRUE(mentions(input.takeMessages(), "warning: no performer found"));
}

// A live camera with nobody in view would wait for ever: Ctrl-C (the cancel predicate) ends the wait, and the
// input starts where it is instead of hanging.
TEST(WandInput, AWaitForAPerformerEndsWhenCancelled) {
  auto nobody = [](double t) {
    HandSample s;
    s.time = t;
    return s;
  };
  int polls = 0;
  PerformerWait wait;
  wait.enabled = true;
  wait.say = [](const std::string&) {};
  wait.cancelled = [&] { return ++polls > 20; };
  StabilizedWands input(std::make_unique<FunctionSource>(nobody, 1000000000, false), StabilizerOptions{}, Calibration{},
                        wait);
  EXPECT_EQ(polls, 21);
  EXPECT_FALSE(input.performerFound());
  EXPECT_TRUE(mentions(input.takeMessages(), "warning: no performer found"));
}

// The performer is found in a sure pose: both hands found, each at least 0.6 sure (a hand followed onto a knee is
// less). Centred then, the calibration follows them when they walk 0.6 m sideways and stay there, gliding after them
// so that the wands never jump; a squat (their median point going down) is not a walk.
TEST(WandInput, ThePerformerIsFoundInASurePoseAndFollowedWhenTheyWalk) {
  auto walker = [](double t) {
    const double walk = std::clamp(t - 12.0, 0.0, 0.6), squat = t > 15.0 ? 0.4 : 0.0;
    HandSample s;
    s.time = t;
    s.left.position = Vec3d(0.25 + walk, -squat, 2.0);
    s.right.position = Vec3d(-0.25 + walk, -squat, 2.0);
    for (HandObservation* h : {&s.left, &s.right}) {
      h->measured = true;
      h->confidence = t < 10.5 - 1e-9 ? 0.4 : 0.9;
    }
    s.body = Vec3d(walk, -0.3 - squat, 2.1);
    return s;
  };
  Calibration c;
  c.autoPerformer = true;
  PerformerWait wait;
  wait.enabled = true;
  wait.say = [](const std::string&) {};
  StabilizedWands input(std::make_unique<FunctionSource>(walker, 240, false), StabilizerOptions{}, c, wait);
  ASSERT_TRUE(input.performerFound());
  EXPECT_NEAR(*input.performerFound(), 0.5, 1e-9);  // the first sure sample, not the first with both hands
  EXPECT_NEAR(input.calibration().performer.x(), 0.0, 1e-9);
  std::vector<std::string> messages;
  Vec3 previous = input.at(0.0).wands.leftPosition;
  double largestStep = 0.0;
  for (double t = 0.02; t < 7.0; t += 0.02) {
    const Vec3 p = input.at(t).wands.leftPosition;
    largestStep = std::max(largestStep, double((p - previous).norm()));
    previous = p;
    for (const std::string& m : input.takeMessages()) messages.push_back(m);
    if (t > 4.2 && t < 4.3) {  // source time 14.7: walked at 12-12.6, stood 0.3 m away from 12.3 on
      EXPECT_NEAR(input.calibration().performer.x(), 0.6, 1e-6);
    }
  }
  EXPECT_TRUE(mentions(messages, "note: the performer moved")) << (messages.empty() ? "" : messages.front());
  EXPECT_NEAR(input.calibration().performer.x(), 0.6, 1e-6);
  EXPECT_NEAR(input.calibration().performer.y(), 0.0, 1e-9);  // the squat was not followed
  // No jump: the tips' own limit (3 m/s) plus the glide's (0.5 m/s of hand space, 1 m/s at reach 2), 0.08 m a frame.
  EXPECT_LE(largestStep, (StabilizerOptions{}.tipSpeed + StabilizedWands::kRecentreSpeed * c.reach) * 0.02 + 1e-4);
}

TEST(ThreadedHandSource, PassesEverySampleOnInOrderThenTheFailure) {
  ThreadedHandSource threaded(std::make_unique<FunctionSource>(moving, 30, true));
  EXPECT_EQ(threaded.describe(), "function");
  for (int k = 0; k < 30; ++k) {
    const std::optional<HandSample> s = threaded.next();
    ASSERT_TRUE(s);
    EXPECT_DOUBLE_EQ(s->time, 10.0 + k / 30.0);
    EXPECT_TRUE(threaded.arrivedAt());
  }
  EXPECT_THROW(threaded.next(), HandSourceLost);  // the camera's failure, after the samples it gave
  EXPECT_TRUE(threaded.ready());
}

// A camera that delivers a sample each time the test lets it: until then its read blocks, as a Kinect's does while
// it waits for its next frame.
class GatedCamera : public HandSource {
 public:
  std::optional<HandSample> next() override {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return allowed_ > given_ || closed_; });
    if (closed_) return std::nullopt;
    return moving(10.0 + given_++ / 30.0);
  }
  [[nodiscard]] std::string describe() const override { return "gated camera"; }
  void allow(int samples) {
    {
      const std::lock_guard lock(mutex_);
      allowed_ += samples;
    }
    changed_.notify_all();
  }
  int given() {
    const std::lock_guard lock(mutex_);
    return given_;
  }
  void close() {
    {
      const std::lock_guard lock(mutex_);
      closed_ = true;
    }
    changed_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  int allowed_ = 0, given_ = 0;
  bool closed_ = false;
};

// The show's frame loop keeps the wall clock: it takes the hands that have arrived and never waits for the camera's
// next frame, however far its own time runs ahead; the hands' age says how old they are.
TEST(WandInput, OnTheWallClockTheFrameLoopNeverWaitsForTheCamera) {
  auto owned = std::make_unique<GatedCamera>();
  GatedCamera* camera = owned.get();
  camera->allow(10);
  StabilizedWands input(std::make_unique<ThreadedHandSource>(std::move(owned)), StabilizerOptions{}, Calibration{});
  input.followWallClock(true);
  while (camera->given() < 10) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the thread has queued all ten
  // Each call must return although the camera gives nothing more: a blocking read would never return. 5 s is a
  // hang, not a slow machine.
  double age = 0.0;
  for (int k = 1; k <= 5; ++k) {
    auto frame = std::async(std::launch::async, [&] { return input.at(1.0 * k); });  // far past the samples
    ASSERT_EQ(frame.wait_for(std::chrono::seconds(5)), std::future_status::ready) << "at() waited for the camera";
    const WandFrame f = frame.get();
    EXPECT_GE(f.handsAge, age);  // the newest hands only get older while no frame comes
    age = f.handsAge;
    EXPECT_TRUE(f.wands.leftPosition.allFinite());
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_GT(age, 0.04);  // at least the 50 ms slept since the tenth sample arrived
  // The camera delivers again: its hands are taken at once, young.
  camera->allow(1);
  while (camera->given() < 11) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_LT(input.at(6.0).handsAge, age);
  camera->close();  // its read returns, so that the thread ends
}

TEST(PointerHandSource, DraggingMovesOnlyTheHeldHandWithoutAJump) {
  double now = 0.0;
  Calibration c;
  PointerHandSource pointer(c, [&] { return now; });
  const HandSample rest = *pointer.next();
  EXPECT_LT((rest.left.position - c.restHand(Hand::Left)).norm(), 1e-12);
  pointer.setPointer(0.9, 0.1);  // no button: nothing moves
  now = 0.1;
  EXPECT_EQ(pointer.next()->left.position, rest.left.position);
  pointer.setButton(Hand::Left, true);
  pointer.setPointer(0.8, 0.1);  // drag a tenth of the window to the left: the window spans 1 m times the reach
  pointer.pushHands(0.2);
  now = 0.2;
  const HandSample moved = *pointer.next();
  EXPECT_EQ(moved.right.position, rest.right.position);
  const Vec3d world = c.toWorld(moved.left.position) - c.toWorld(rest.left.position);
  EXPECT_NEAR(world.x(), -0.1 * c.reach, 1e-12);  // the window's left, as seen from the front
  EXPECT_NEAR(world.y(), 0.0, 1e-12);
  EXPECT_NEAR(world.z(), 0.2 * c.reach, 1e-12);  // pushed towards the camera: forward
  EXPECT_GT(moved.time, rest.time);
}

}  // namespace
}  // namespace gb

namespace gb {
namespace {

// A scripted performance sampled at `rate` per second, noiseless, in camera space.
std::vector<HandSample> sampledAt(double rate, double seconds, const ScriptedHandSource& script) {
  std::vector<HandSample> samples;
  for (int i = 0; i * (1.0 / rate) <= seconds; ++i) samples.push_back(script.truth(i / rate));
  return samples;
}

struct RateRun {
  double lag = 0.0;      // s behind the truth, at the run's frames
  double fastest = 0.0;  // m/s, largest wand speed between two run frames (camera space)
  int longestStill = 0;  // run frames in a row in which the left wand did not move while the hand did
  std::vector<std::string> messages;
};

// The input through StabilizedWands, read at the run loop's 50 frames per second, as `giantbubble run` does.
RateRun runAt(double rate) {
  GestureOptions gesture;
  Calibration calibration;
  const ScriptedHandSource script(Gesture::Circles, gesture, calibration, rate);
  StabilizedWands wands(std::make_unique<ReplayHandSource>(sampledAt(rate, 6.0, script), "scripted"),
                        StabilizerOptions{}, calibration);
  constexpr double kFrame = 1.0 / 50.0;
  RateRun r;
  std::vector<Vec3d> truth, wand;
  int still = 0;
  for (int i = 0; i * kFrame <= 5.5; ++i) {
    const double t = i * kFrame;
    const WandFrame f = wands.at(t);
    const Vec3d p = calibration.toCamera(f.wands.leftPosition.cast<double>());
    if (!wand.empty()) {
      const double step = (p - wand.back()).norm();
      r.fastest = std::max(r.fastest, step / kFrame);
      // The hand is moving, and has been for longer than the stabilizer's lag (the stroke starts at 0.5 s).
      const bool handMoved = t > 1.0 && (script.truth(t).left.position - truth.back()).norm() > 1e-4;
      still = step < 1e-6 && handMoved ? still + 1 : 0;
      r.longestStill = std::max(r.longestStill, still);
    }
    truth.push_back(script.truth(t).left.position);
    wand.push_back(p);
  }
  // Lag over the circles themselves (after the first second's start-up).
  const std::vector<Vec3d> leader(truth.begin() + 50, truth.end()), follower(wand.begin() + 50, wand.end());
  r.lag = lag(leader, follower, kFrame, 0.6);
  r.messages = wands.takeMessages();
  return r;
}

// From 7.5 to 60 samples per second the wands neither freeze nor teleport (never faster than the
// stabilizer's speed limit, never a run frame standing still while the hand moves), lag at most 100 ms at
// 30 Hz and 150 ms at 15 Hz (plus one run frame, 20 ms, the resolution the lag is seen at), and a rate below
// 25 Hz is warned about.
TEST(WandInput, EveryInputRateFrom7p5To60HzGivesSmoothWandsWithinTheirLag) {
  const StabilizerOptions limits;
  for (const double rate : {7.5, 10.0, 15.0, 20.0, 25.0, 30.0, 60.0}) {
    const RateRun r = runAt(rate);
    std::printf("%5.1f Hz: lag %.0f ms, fastest %.2f m/s, longest still %d frames\n", rate, 1e3 * r.lag, r.fastest,
                r.longestStill);
    EXPECT_LE(r.fastest, limits.maxSpeed + 1e-6) << rate;
    EXPECT_EQ(r.longestStill, 0) << rate;
    if (rate >= 30.0) {
      EXPECT_LE(r.lag, 0.100 + 0.02) << rate;
    } else if (rate >= 15.0) {
      EXPECT_LE(r.lag, 0.150 + 0.02) << rate;
    }
    EXPECT_EQ(mentions(r.messages, "below 25"), rate < 25.0) << rate;
  }
}

}  // namespace
}  // namespace gb
