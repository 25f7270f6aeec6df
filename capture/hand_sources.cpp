#include "capture/hand_sources.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "capture/trajectory_file.h"
#include "capture/untrusted.h"

namespace gb {

HandObservation HandHold::update(double t, const std::optional<Vec3d>& measurement, double confidence) {
  HandObservation o;
  if (measurement) {
    last_ = *measurement;
    lastTime_ = t;
    lastConfidence_ = confidence;
    o.position = last_;
    o.confidence = confidence;
    o.measured = true;
    return o;
  }
  o.position = last_;
  o.confidence = o.seen() ? lastConfidence_ * std::exp(-(t - lastTime_) / holdTime_) : 0.0;
  return o;
}

DepthHandSource::DepthHandSource(std::unique_ptr<DepthStream> stream, const DetectionOptions& detection,
                                 const TrackerOptions& tracker)
    : stream_(std::move(stream)), finder_(detection, tracker) {}

std::optional<HandSample> DepthHandSource::next() {
  try {
    return nextSample();
  } catch (const HandSourceLost&) {
    stream_->release();  // so that the camera, back again, can be opened anew (the live window reopens it)
    throw;
  }
}

std::optional<HandSample> DepthHandSource::nextSample() {
  while (true) {
    // A camera slower than 30 Hz (a busy USB bus, a 15 Hz mode) is late by its own measure, not by 30 Hz's.
    const double timeout = std::max(kFrameTimeout, 2.5 * frameInterval_);
    switch (stream_->poll(frame_, timeout)) {
      case DepthStream::Poll::End:
        return std::nullopt;
      case DepthStream::Poll::Nothing: {
        // A live camera late with its frame: both hands held; lost for good after kLostAfter.
        const double now = stream_->clock();
        if (now - lastFrame_ > kLostAfter) {
          char text[96];
          std::snprintf(text, sizeof text, "no depth frame from the Kinect for %.1f s (unplugged?)", now - lastFrame_);
          throw HandSourceLost(text);
        }
        return finder_.miss(now);
      }
      case DepthStream::Poll::Frame:
        if (lastFrame_ > 0.0 && frame_.time > lastFrame_ && frame_.time - lastFrame_ < 1.0)
          frameInterval_ = frameInterval_ == 0.0 ? frame_.time - lastFrame_
                                                 : frameInterval_ + 0.2 * (frame_.time - lastFrame_ - frameInterval_);
        lastFrame_ = frame_.time;
        if (observer_) observer_(frame_);
        if (frame_.gravityUp) checkGravity();
        if (!gravityBelieved_) frame_.gravityUp.reset();
        return finder_.update(frame_);
    }
  }
}

void DepthHandSource::checkGravity() {
  const SegmentationOptions& segmentation = finder_.options().segmentation;
  if (segmentation.gravityUp || framesToGravityCheck_-- > 0) return;
  const std::optional<FloorPlane> along = floorOf(frame_, segmentation, frame_.gravityUp);
  const std::optional<FloorPlane> searched = floorOf(frame_, segmentation, std::nullopt);
  if (!along || !searched) return;  // no floor in view: nothing to check against, the next frame tries again
  framesToGravityCheck_ = kGravityCheckEvery;
  const double degrees = std::acos(std::clamp(along->up.dot(searched->up), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  const bool agrees = degrees <= kGravityAgreement;
  if (!agrees && gravityBelieved_) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "warning: the accelerometer's gravity is %.0f degrees from the floor in view; the floor is "
                  "found from the depth instead",
                  degrees);
    messages_.push_back(text);
  }
  gravityBelieved_ = agrees;
}

std::string DepthHandSource::whyNoHands() const {
  const Detection& d = finder_.detection();
  std::string why = d.performerPixels == 0 ? d.why : d.why + ", no hand found on it";
  if (!d.advice.empty()) why += " (" + d.advice + ")";
  return why;
}

ReplayHandSource::ReplayHandSource(std::vector<HandSample> samples, std::string describe,
                                   std::vector<std::string> messages)
    : samples_(std::move(samples)), describe_(std::move(describe)), messages_(std::move(messages)) {}

std::optional<HandSample> ReplayHandSource::next() {
  if (next_ >= samples_.size()) return std::nullopt;
  return samples_[next_++];
}

std::optional<double> ReplayHandSource::length() const {
  if (samples_.empty()) return 0.0;
  return samples_.back().time - samples_.front().time;
}

double ReplayHandSource::period() const {
  if (samples_.size() < 2) return 1.0 / 30.0;
  return *length() / static_cast<double>(samples_.size() - 1);
}

std::unique_ptr<HandSource> openTrajectory(const std::filesystem::path& path, const TrajectoryLimits& limits) {
  std::string cut;
  std::vector<HandSample> samples = readTrajectory(path, 0.5, limits, &cut);
  char describe[64];
  std::snprintf(describe, sizeof describe, " (%zu samples, %.2f s)", samples.size(),
                samples.back().time - samples.front().time);
  std::vector<std::string> messages;
  if (!cut.empty()) messages.push_back(cut);
  return std::make_unique<ReplayHandSource>(std::move(samples), "trajectory file " + printablePath(path) + describe,
                                            std::move(messages));
}

ScriptedHandSource::ScriptedHandSource(Gesture gesture, const GestureOptions& options, const Calibration& calibration,
                                       double rate, const SourceNoise& noise)
    : gesture_(gesture), options_(options), calibration_(calibration), rate_(rate), noise_(noise), random_(noise.seed) {
  describe_ = "scripted gesture";
  for (const std::string& name : gestureNames())
    if (gestureFromName(name) == gesture) describe_ += " '" + name + "'";
  if (noise.sigma > 0 || noise.outlierRate > 0) {
    char text[96];
    std::snprintf(text, sizeof text, " with %.2g cm noise and %.2g%% outliers of %.2g cm", 100 * noise.sigma,
                  100 * noise.outlierRate, 100 * noise.outlierDistance);
    describe_ += text;
  }
}

HandSample ScriptedHandSource::truth(double t) const {
  const WandState w = gestureAt(gesture_, options_, t);
  HandSample s;
  s.time = t;
  s.left.position = calibration_.toCamera(w.leftPosition.cast<double>());
  s.right.position = calibration_.toCamera(w.rightPosition.cast<double>());
  for (HandObservation* h : {&s.left, &s.right}) {
    h->confidence = 1.0;
    h->measured = true;
  }
  return s;
}

namespace {

// Three standard normal draws as a vector, drawn z, y, x. Not Vec3d(gauss(r), gauss(r), gauss(r)): the order in
// which a constructor's arguments are evaluated is unspecified (gcc right to left, clang left to right), which
// gave each compiler different noise and different test figures. z, y, x is gcc's order, which every figure
// measured so far used.
Vec3d gaussianVector(std::normal_distribution<double>& gauss, std::mt19937& random) {
  const double z = gauss(random);
  const double y = gauss(random);
  const double x = gauss(random);
  return {x, y, z};
}

}  // namespace

std::optional<HandSample> ScriptedHandSource::next() {
  HandSample s = truth(static_cast<double>(index_++) / rate_);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (HandObservation* h : {&s.left, &s.right}) {
    // The same draws whatever the settings, so that runs differing only in outliers share their noise.
    const Vec3d noise = gaussianVector(gauss, random_);
    const Vec3d direction = gaussianVector(gauss, random_).normalized();
    const bool outlier = uniform(random_) < noise_.outlierRate;
    h->position += noise_.sigma * noise + (outlier ? noise_.outlierDistance : 0.0) * direction;
  }
  return s;
}

PointerHandSource::PointerHandSource(const Calibration& calibration, std::function<double()> clock)
    : clock_(std::move(clock)), calibration_(calibration) {
  if (!clock_) {
    const auto start = std::chrono::steady_clock::now();
    clock_ = [start] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  }
  hands_[0] = calibration.restHand(Hand::Left);
  hands_[1] = calibration.restHand(Hand::Right);
}

Vec3d PointerHandSource::anchorOf(int hand) const {
  // The pointer's point on the plane through the hand parallel to the image, world x right and y up: the
  // window spans 1 m of hand motion, `reach` metres of world.
  const Vec3d world = calibration_.toWorld(hands_[hand]);
  const double across = calibration_.reach * 1.0;
  const Vec3d onPlane(calibration_.anchor.x() + (pointer_[0] - 0.5) * across,
                      calibration_.anchor.y() + (0.5 - pointer_[1]) * across, world.z());
  return calibration_.toCamera(onPlane);
}

void PointerHandSource::setPointer(double x, double y) {
  std::lock_guard lock(mutex_);
  Vec3d before[2] = {anchorOf(0), anchorOf(1)};
  pointer_[0] = x;
  pointer_[1] = y;
  for (int h = 0; h < 2; ++h)
    if (held_[h]) hands_[h] += anchorOf(h) - before[h];  // a drag: the hand moves with the pointer, no jump
}

void PointerHandSource::setButton(Hand hand, bool down) {
  std::lock_guard lock(mutex_);
  held_[static_cast<int>(hand)] = down;
}

void PointerHandSource::pushHands(double metres) {
  std::lock_guard lock(mutex_);
  for (int h = 0; h < 2; ++h)
    if (held_[h]) hands_[h].z() -= metres;  // towards the camera is the performer's forward
}

std::optional<HandSample> PointerHandSource::next() {
  std::lock_guard lock(mutex_);
  HandSample s;
  s.time = std::max(clock_(), lastTime_);
  lastTime_ = s.time;
  for (int h = 0; h < 2; ++h) {
    HandObservation& o = s.hand(h == 0 ? Hand::Left : Hand::Right);
    o.position = hands_[h];
    o.confidence = 1.0;
    o.measured = true;
  }
  return s;
}

std::unique_ptr<HandSource> makeHandSource(const std::string& spec, const SourceOptions& o) {
  const size_t colon = spec.find(':');
  const std::string kind = spec.substr(0, colon), argument = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (kind == "kinect" && colon == std::string::npos)
    return std::make_unique<DepthHandSource>(DepthStream::openKinect(), o.detection, o.tracker);
  if (colon != std::string::npos && argument.empty())
    throw HandSourceError("input '" + spec + "': nothing after the colon");
  if (kind == "fakenect" && colon != std::string::npos)
    return std::make_unique<DepthHandSource>(DepthStream::openRecording(argument), o.detection, o.tracker);
  if (kind == "trajectory" && colon != std::string::npos) return openTrajectory(argument, o.trajectory);
  if (kind == "script" && colon != std::string::npos) {
    try {
      return std::make_unique<ScriptedHandSource>(gestureFromName(argument), o.gesture, o.calibration, 30.0, o.noise);
    } catch (const std::invalid_argument& e) {
      throw HandSourceError(e.what());
    }
  }
  throw HandSourceError("unknown input '" + spec + "' (expected kinect, fakenect:DIR, trajectory:FILE or script:NAME)");
}

}  // namespace gb
