#pragma once
// What moves the wands of a run, frame by frame, in world space: a scripted gesture directly, or any hand
// source through the stabilizer and the calibration. The run loop asks for the wands at its own frame times;
// StabilizedWands reads the source up to that time and carries the wands on between samples by Eq. (1).
//
// Failures mid-performance never stop a run: when the source is lost (camera unplugged, recording file gone)
// or ends, the wands come to rest and hold still, and a message says so; a hand not seen for a while, and its
// return, are reported the same way.

#include <array>
#include <cmath>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "capture/calibration.h"
#include "capture/hand_source.h"
#include "capture/scripted_gestures.h"
#include "capture/stabilizer.h"

namespace gb {

struct WandFrame {
  WandState wands;                      // world space
  Vec3 leftHand = Vec3::Constant(NAN);  // the newest measured input hands, world space (NaN: not measured)
  Vec3 rightHand = Vec3::Constant(NAN);
  double handsAge = 0.0;  // s since the newest hands arrived from a camera read beside the frame loop (0: not known)
  // The performer's depth points, world space, mapped as the hands are, from the newest depth frame taken (none
  // without a depth camera), and that frame's run time.
  std::shared_ptr<const std::vector<Vec3>> body;
  double bodyTime = 0.0;
};

class WandInput {
 public:
  virtual ~WandInput() = default;
  // The wands at run time t (s, from 0, not decreasing between calls).
  virtual WandFrame at(double t) = 0;
  [[nodiscard]] virtual std::string describe() const = 0;
  // Seconds of input a recorded source holds; nothing for scripts and live sources.
  [[nodiscard]] virtual std::optional<double> length() const { return std::nullopt; }
  // Whether the input has ended or was lost (the wands at rest); scripts never end.
  [[nodiscard]] virtual bool ended() const { return false; }
  // Where the camera stands in the world, for inputs seen by one (camera space carried by the calibration).
  [[nodiscard]] virtual std::optional<Vec3> camera() const { return std::nullopt; }
  // The calibration that carries the camera's space into the world, for inputs seen by one (nullptr: none).
  [[nodiscard]] virtual const Calibration* cameraCalibration() const { return nullptr; }
  // Seconds of input read before the performer was found (run time 0 is then), when waited for.
  [[nodiscard]] virtual std::optional<double> performerFound() const { return std::nullopt; }
  // Whether each hand (left, right) has gone unmeasured for kLostHandAfter and is held (reported lost).
  [[nodiscard]] virtual std::array<bool, 2> handsLost() const { return {false, false}; }
  // Warnings and notes since the last call, each one line ("warning: …" or "note: …").
  std::vector<std::string> takeMessages() { return std::exchange(messages_, {}); }

 protected:
  std::vector<std::string> messages_;
};

class ScriptedWands : public WandInput {
 public:
  ScriptedWands(Gesture gesture, const GestureOptions& options) : gesture_(gesture), options_(options) {}
  WandFrame at(double t) override;
  [[nodiscard]] std::string describe() const override;

 private:
  Gesture gesture_;
  GestureOptions options_;
};

// Where the messages go while a performer is waited for: the caller cannot print them until the wait is over.
using MessageSink = std::function<void(const std::string&)>;
void printToStderr(const std::string& message);

// Waiting for a performer before run time 0 (StabilizedWands).
struct PerformerWait {
  bool enabled = false;
  MessageSink say = printToStderr;  // "waiting for a performer: …", once per second of input
  std::function<bool()> cancelled;  // polled while waiting: true stops the wait (Ctrl-C), the run starts as is
  // The set-up step of a show with a live camera: the sure pose held this long (s), the hands within kHeldStill of
  // where they were when it began, before the performer is taken; say() counts it down ("hold both hands forward
  // and still: 3", 2, 1). 0: the first sure pose is taken (a recording, a file).
  double holdStill = 0.0;
  static constexpr double kHeldStill = 0.15;  // m each hand may move while held
};

class StabilizedWands : public WandInput {
 public:
  // With wait.enabled, run time 0 is the first sample with both hands measured; the samples before it are
  // dropped, so the wands (and the film made on them) start at the performer's hands rather than between one
  // hand and the other's rest pose. While waiting, wait.say gets "waiting for a performer: …" once per second
  // of input; an input that ends (or a wait cancelled) without both hands starts where it is, with a warning.
  // With calibration.autoPerformer the calibration is centred between the hands of that sample (without the
  // wait: of the first sample with both hands within 3 s).
  StabilizedWands(std::unique_ptr<HandSource> source, const StabilizerOptions& stabilizer,
                  const Calibration& calibration, const PerformerWait& wait = {});
  WandFrame at(double t) override;
  [[nodiscard]] std::string describe() const override;
  [[nodiscard]] std::optional<double> length() const override;
  [[nodiscard]] std::optional<double> performerFound() const override { return performerFound_; }
  [[nodiscard]] std::array<bool, 2> handsLost() const override { return {reportedLost_[0], reportedLost_[1]}; }
  [[nodiscard]] std::optional<Vec3> camera() const override {
    return calibration_.toWorld(Vec3d::Zero()).cast<float>();
  }
  [[nodiscard]] const Calibration& calibration() const { return calibration_; }
  [[nodiscard]] const Calibration* cameraCalibration() const override { return &calibration_; }
  [[nodiscard]] double confidence(Hand hand) const { return stabilizer_->confidence(hand); }
  // The frame loop keeps the wall clock (live, run --realtime): with a source read on a thread of its own
  // (ThreadedHandSource), at() takes the samples that have arrived and never waits for the next one; past the newest
  // the wands are carried on by Eq. (1). The first call starts at the newest hands (not at those of when the input
  // opened, before the film and the window were made), and run time then maps onto the input's time one to one, so
  // the wands never jump; a loop that falls behind the input catches up at 1 + kCatchUp times its own pace, and one
  // that runs ahead of it (the camera's thread starved of a core) waits a period past the newest sample, the wands
  // carried on by Eq. (1), rather than passing samples by. Otherwise at(t) reads the source up to run time t, waiting
  // where it must.
  void followWallClock(bool follow) { wallClock_ = follow; }
  // The input's time runs this much faster than the loop's while the loop is behind it (frames it dropped): 5% faster
  // wands barely change a film (20% faster ones burst films that lived), and a second of lag is gone in 20.
  static constexpr double kCatchUp = 0.05;

  static constexpr double kLostHandAfter = 0.25;  // s unmeasured before a hand is reported lost
  // A performer found in depth who walks this far (m, across or along the camera's view; a squat or a raised arm
  // moves their median point up and down, not this way) and stays there this long (s) is centred on again: the
  // calibration glides after them at kRecentreSpeed (m/s of hand space), so the wands never jump.
  static constexpr double kMovedDistance = 0.3;
  static constexpr double kMovedTime = 1.0;
  static constexpr double kRecentreSpeed = 0.5;
  static constexpr double kSlowRate = 25.0;  // samples per second below which the input is reported slow
  // Samples closer than this (s) to the last one fed are skipped, and holds through a gap go at least this far
  // apart: an input with samples 1 ns apart would otherwise cost millions of stabilizer updates per frame.
  static constexpr double kMinSamplePeriod = 1e-3;
  // The source ended or was lost, and every sample read is used: the wands hold still from here on.
  [[nodiscard]] bool ended() const override { return finished_ && ahead_.empty(); }

 private:
  std::unique_ptr<HandSource> source_;
  Calibration calibration_;
  std::unique_ptr<Stabilizer> stabilizer_;
  std::deque<HandSample> ahead_;  // read from the source, not yet given to the stabilizer
  bool finished_ = false;         // the source ended or was lost: only holds from here on
  double start_ = 0.0;            // source time at run time 0
  double first_ = 0.0;            // source time of the first sample read
  std::optional<double> performerFound_;
  double lastFed_ = 0.0;        // source time of the newest sample the stabilizer has
  double period_ = 1.0 / 30.0;  // s between samples: the source's nominal period, then as observed
  int intervals_ = 0;           // sample intervals observed
  bool reportedSlow_ = false;
  double lastMeasured_[2] = {0.0, 0.0};
  bool reportedLost_[2] = {false, false};
  HandSample latest_;
  // The newest sample's body points in the world, made once per depth frame (at).
  std::shared_ptr<const std::vector<Eigen::Vector3f>> bodyInCamera_;
  std::shared_ptr<const std::vector<Vec3>> bodyInWorld_;
  double bodyTime_ = 0.0;
  std::string describe_;
  [[nodiscard]] double period() const;  // the source's, at least kMinSamplePeriod
  bool fetch();                         // reads one more sample into ahead_; false when there are no more
  void waitForPerformer(const PerformerWait& wait);
  void centreOnPerformer(const HandSample& sample);
  void feed(const HandSample& sample);
  void followPerformer(const HandSample& sample, double dt);  // re-centres on a performer who walked
  void take(const HandSample& sample, double period);         // feeds a sample read, with the holds of a gap before it
  void holdUntil(double until, double period);    // both hands held where they were, up to source time until
  void observeInterval(double dt);                // updates period_ and warns once about a slow input
  double wallClockTime(double t, double period);  // wall-clock mode: the source time of run time t
  bool wallClock_ = false;
  bool aligned_ = false;  // wall-clock mode: offset_ taken at the first call
  double offset_ = 0.0;   // s the input's time runs ahead of start_ + t
  double lastT_ = 0.0;
  std::optional<Vec3d> centreFromBody_;  // calibration.performer less the performer's median point, when centred
  double movedFor_ = 0.0;                // s the performer has stood kMovedDistance from where they were centred
  bool recentring_ = false;
  double newestSample_ = 0.0;  // source time of the newest sample read (not a hold)
};

}  // namespace gb
