#pragma once
// The hand sources behind HandSource, and makeHandSource, which opens one from a command-line spec:
//   kinect            live Kinect v1 through libfreenect
//   fakenect:DIR      a fakenect recording played through libfreenect's fakenect library
//   trajectory:FILE   a trajectory CSV (trajectory_file.h)
//   script:NAME       a built-in gesture (scripted_gestures.h), carried into camera space by the calibration
// The mouse-and-keyboard source (PointerHandSource) is made by the live window, not from a spec.

#include <functional>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <utility>

#include "capture/calibration.h"
#include "capture/freenect_stream.h"
#include "capture/hand_finder.h"
#include "capture/scripted_gestures.h"
#include "capture/trajectory_file.h"

namespace gb {

// Depth frames -> hands: the same code for a live Kinect and for a fakenect recording.
class DepthHandSource : public HandSource {
 public:
  DepthHandSource(std::unique_ptr<DepthStream> stream, const DetectionOptions& detection,
                  const TrackerOptions& tracker);
  std::optional<HandSample> next() override;
  [[nodiscard]] std::string describe() const override { return stream_->describe(); }
  // Called with every depth frame before detection (giantbubble record writes them as a fakenect recording).
  void onFrame(std::function<void(const kinect::DepthFrame&)> observer) { observer_ = std::move(observer); }
  [[nodiscard]] std::optional<double> length() const override { return stream_->length(); }
  // "no body in the depth band 0.5-4.0 m", or where the body is when it has no hand.
  [[nodiscard]] std::string whyNoHands() const override;
  std::vector<std::string> takeMessages() override { return std::exchange(messages_, {}); }
  // What the newest frame showed: the performer taken and why, the hands found.
  [[nodiscard]] const Detection& detection() const { return finder_.detection(); }

  static constexpr double kFrameTimeout = 0.1;  // s without a frame (or 2.5 frame intervals, if longer): a
                                                //   sample with both hands held
  static constexpr double kLostAfter = 2.0;     // s without a frame: the camera is lost (HandSourceLost)

 private:
  std::unique_ptr<DepthStream> stream_;
  HandFinder finder_;
  kinect::DepthFrame frame_;
  double lastFrame_ = 0.0;
  double frameInterval_ = 0.0;  // s between depth frames, smoothed (0: not known yet)
  std::function<void(const kinect::DepthFrame&)> observer_;
  std::optional<HandSample> nextSample();  // next() but for letting go of a lost camera
  // The accelerometer is believed while it agrees with the floor found in the depth without it: checked on
  // the first frame that has both, then every kGravityCheckEvery frames; a disagreement is warned about once.
  void checkGravity();
  static constexpr int kGravityCheckEvery = 150;    // frames (5 s at 30 Hz)
  static constexpr double kGravityAgreement = 5.0;  // degrees between the two floors' normals
  bool gravityBelieved_ = true;
  int framesToGravityCheck_ = 0;
  std::vector<std::string> messages_;
};

// Samples already in memory, played in order: a trajectory file, or a recorded session replayed.
class ReplayHandSource : public HandSource {
 public:
  // `messages` are passed on by the first takeMessages(), e.g. a note that the file was not read to its end.
  ReplayHandSource(std::vector<HandSample> samples, std::string describe, std::vector<std::string> messages = {});
  std::optional<HandSample> next() override;
  [[nodiscard]] std::string describe() const override { return describe_; }
  [[nodiscard]] double period() const override;
  [[nodiscard]] std::optional<double> length() const override;
  std::vector<std::string> takeMessages() override { return std::exchange(messages_, {}); }

 private:
  std::vector<HandSample> samples_;
  std::string describe_;
  std::vector<std::string> messages_;
  size_t next_ = 0;
};

// A trajectory CSV (trajectory_file.h), read when opened, as far as `limits` allow, so that a malformed file fails
// before the run.
std::unique_ptr<HandSource> openTrajectory(const std::filesystem::path& path, const TrajectoryLimits& limits = {});

// Noise for a scripted source: what a depth camera would add, to measure the stabilizers against the truth.
struct SourceNoise {
  double sigma = 0.0;            // m, Gaussian, per coordinate
  double outlierRate = 0.0;      // probability per hand and sample of an outlier
  double outlierDistance = 0.2;  // m, how far an outlier lands from the truth (random direction)
  unsigned seed = 1;
};

class ScriptedHandSource : public HandSource {
 public:
  ScriptedHandSource(Gesture gesture, const GestureOptions& options, const Calibration& calibration, double rate = 30.0,
                     const SourceNoise& noise = {});
  std::optional<HandSample> next() override;  // never ends
  [[nodiscard]] std::string describe() const override { return describe_; }
  [[nodiscard]] double period() const override { return 1.0 / rate_; }
  [[nodiscard]] HandSample truth(double t) const;  // noiseless, camera space

 private:
  Gesture gesture_;
  GestureOptions options_;
  Calibration calibration_;
  double rate_;
  SourceNoise noise_;
  std::mt19937 random_;
  long index_ = 0;
  std::string describe_;
};

// The mouse and keyboard seam for the live window: the window's event callbacks move the hands, the simulation
// reads them through HandSource like any other input. The pointer is in normalised window coordinates
// ((0, 0) top left, (1, 1) bottom right) and maps onto a camera-space plane at the performer's depth, one
// metre across; the held button picks the hand (left button: left hand, right button: right hand, both: both);
// pushHands moves the picked hands towards (+) or away from (-) the camera (keys or the wheel).
class PointerHandSource : public HandSource {
 public:
  explicit PointerHandSource(const Calibration& calibration, std::function<double()> clock = {});
  void setPointer(double x, double y);
  void setButton(Hand hand, bool down);
  void pushHands(double metres);
  std::optional<HandSample> next() override;  // the current state, now; never ends
  [[nodiscard]] std::string describe() const override { return "mouse and keyboard"; }

 private:
  std::mutex mutex_;  // the window's thread writes, the simulation's reads
  std::function<double()> clock_;
  Calibration calibration_;
  Vec3d hands_[2];
  bool held_[2] = {false, false};
  double pointer_[2] = {0.5, 0.5};
  double lastTime_ = -1.0;
  Vec3d anchorOf(int hand) const;
};

struct SourceOptions {
  DetectionOptions detection;
  TrackerOptions tracker;
  Calibration calibration;  // carries scripted gestures into camera space
  GestureOptions gesture;
  SourceNoise noise;            // scripted sources only
  TrajectoryLimits trajectory;  // how much of a trajectory file is read
};

// Opens "kinect", "fakenect:DIR", "trajectory:FILE" or "script:NAME"; throws HandSourceError with what went wrong.
std::unique_ptr<HandSource> makeHandSource(const std::string& spec, const SourceOptions& options);

}  // namespace gb
