#pragma once
// Where the performer's hands come from: one interface, HandSource, for every input (live Kinect, fakenect
// recording, trajectory file, scripted gesture, mouse and keyboard). A source yields timestamped samples of
// both hands in camera space (kinect_depth.h: x right, y up, z away from the camera, metres); the stabilizer
// turns them into wands and the calibration carries the wands into the simulation's world.

#include <Eigen/Dense>
#include <chrono>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace gb {

using Vec3d = Eigen::Vector3d;

enum class Hand { Left = 0, Right = 1 };  // the performer's own left and right

// One hand in one sample. A hand not measured in this sample is held: it keeps its last measured position
// and its confidence decays as exp(-age / holdTime) (HandHold below), so a consumer never sees a jump.
struct HandObservation {
  Vec3d position = Vec3d::Constant(std::numeric_limits<double>::quiet_NaN());  // camera space (m); NaN never seen
  double confidence = 0.0;  // the detector's (0..1] when measured, decaying while held, 0 when never seen
  bool measured = false;    // measured in this sample (otherwise held or never seen)
  [[nodiscard]] bool seen() const { return position.allFinite(); }
};

struct HandSample {
  double time = 0.0;  // s, increasing along a source
  HandObservation left, right;
  std::optional<Vec3d> body;  // the performer's median point (camera space), where a depth camera found them
  // The performer's depth points (camera space, one per pixel of the detector's half-resolution grid), where a depth
  // camera found them: the body the film can touch. Shared, since a sample is copied along the input's queue.
  std::shared_ptr<const std::vector<Eigen::Vector3f>> bodyPoints;
  HandObservation& hand(Hand h) { return h == Hand::Left ? left : right; }
  [[nodiscard]] const HandObservation& hand(Hand h) const { return h == Hand::Left ? left : right; }
};

// Opening a source failed (missing file, malformed data, no camera): the message says what and where.
struct HandSourceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// A source that was delivering stopped (camera unplugged, recording file gone): mid-performance the wands
// hold still and the run goes on with a warning.
struct HandSourceLost : HandSourceError {
  using HandSourceError::HandSourceError;
};

class HandSource {
 public:
  virtual ~HandSource() = default;
  // The next sample, or nothing at the end of a finite input. Throws HandSourceLost when the input fails.
  virtual std::optional<HandSample> next() = 0;
  // One line for logs: what this source is (e.g. "fakenect recording rec/ (90 depth frames)").
  [[nodiscard]] virtual std::string describe() const = 0;
  // Nominal time between samples (s), for holding the wands when samples stop coming.
  [[nodiscard]] virtual double period() const { return 1.0 / 30.0; }
  // Seconds from the first sample to the last, for a finite recorded input; nothing for a live or endless one.
  [[nodiscard]] virtual std::optional<double> length() const { return std::nullopt; }
  // Warnings and notes since the last call, one line each ("warning: …"), passed on by StabilizedWands.
  virtual std::vector<std::string> takeMessages() { return {}; }
  // Why the newest sample has no hand, for the message shown while a performer is waited for.
  [[nodiscard]] virtual std::string whyNoHands() const { return "no hands in the input"; }
  // Whether next() returns at once. A source read on a thread of its own (ThreadedHandSource) says whether a sample
  // has arrived; the others answer true and take as long as reading takes.
  [[nodiscard]] virtual bool ready() const { return true; }
  // When the sample next() returned last arrived from its thread (steady clock); nothing for a source read in place.
  [[nodiscard]] virtual std::optional<std::chrono::steady_clock::time_point> arrivedAt() const { return std::nullopt; }
};

// Hold and decay, the one definition every source uses for a hand it did not measure: the hand stays at its
// last measured position and its confidence decays exponentially with the time since that measurement.
class HandHold {
 public:
  explicit HandHold(double holdTime = 0.5) : holdTime_(holdTime) {}
  // Measured: its position and confidence (the detector's, 1 for exact inputs). Not measured: the held
  // observation at time t, its confidence decaying from the last measured one.
  HandObservation update(double t, const std::optional<Vec3d>& measurement, double confidence = 1.0);

 private:
  double holdTime_;
  Vec3d last_ = Vec3d::Constant(std::numeric_limits<double>::quiet_NaN());
  double lastTime_ = 0.0;
  double lastConfidence_ = 0.0;
};

}  // namespace gb
