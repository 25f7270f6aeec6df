#include "capture/wand_input.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace gb {

namespace {

std::string seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f s", t);
  return text;
}

const char* handName(int h) { return h == 0 ? "left" : "right"; }

}  // namespace

WandFrame ScriptedWands::at(double t) {
  WandFrame f;
  f.wands = gestureAt(gesture_, options_, t);
  f.leftHand = f.wands.leftPosition;
  f.rightHand = f.wands.rightPosition;
  return f;
}

std::string ScriptedWands::describe() const {
  for (const std::string& name : gestureNames())
    if (gestureFromName(name) == gesture_) return "scripted gesture '" + name + "' (world space, exact)";
  return "scripted gesture";
}

void printToStderr(const std::string& message) { std::fprintf(stderr, "%s\n", message.c_str()); }

namespace {

bool bothMeasured(const HandSample& s) { return s.left.measured && s.right.measured; }

// Both hands measured and each sure (the hand tracker's confidence for a hand it was not following): the pose a
// performer is found in and the calibration is centred on. A hand followed onto something less sure (down to 0.3),
// or a knee at the lower edge of a close camera's image (halved, hand_detector.cpp), does not place the performer.
constexpr double kConfidentHand = 0.6;
bool confidentPose(const HandSample& s) {
  return bothMeasured(s) && s.left.confidence >= kConfidentHand && s.right.confidence >= kConfidentHand;
}

}  // namespace

StabilizedWands::StabilizedWands(std::unique_ptr<HandSource> source, const StabilizerOptions& stabilizer,
                                 const Calibration& calibration, const PerformerWait& wait)
    : source_(std::move(source)), calibration_(calibration), describe_(source_->describe()) {
  if (!fetch())
    throw HandSourceError(describe_ + ": no samples" + (messages_.empty() ? "" : " (" + messages_.back() + ")"));
  start_ = first_ = ahead_.front().time;
  if (wait.enabled) {
    waitForPerformer(wait);
  } else if (calibration_.autoPerformer) {
    while (!confidentPose(ahead_.back()) && ahead_.back().time - start_ < 3.0 && fetch()) {
    }
    if (confidentPose(ahead_.back()))
      centreOnPerformer(ahead_.back());
    else
      messages_.push_back(
          "warning: calibration: no sample with both hands in the first 3 s; the performer stays at "
          "the configured point");
  }
  StabilizerOptions options = stabilizer;
  period_ = source_->period();
  options.period = period();  // at least kMinSamplePeriod: a 1 ns input must not set a 1 ns stabilizer step
  options.maxSpeed = std::min(options.maxSpeed, options.tipSpeed / calibration_.reach);  // the tips' limits, in the
  options.maxAcceleration = std::min(options.maxAcceleration, options.tipAcceleration / calibration_.reach);  // camera
  stabilizer_ =
      std::make_unique<Stabilizer>(options, calibration_.restHand(Hand::Left), calibration_.restHand(Hand::Right));
  lastMeasured_[0] = lastMeasured_[1] = start_;
  feed(ahead_.front());
  newestSample_ = ahead_.front().time;
  ahead_.pop_front();
}

void StabilizedWands::centreOnPerformer(const HandSample& sample) {
  calibration_.performer = 0.5 * (sample.left.position + sample.right.position);
  if (sample.body) centreFromBody_ = calibration_.performer - *sample.body;
  char text[160];
  std::snprintf(text, sizeof text, "note: calibration: performer at (%.2f, %.2f, %.2f) m, between the hands at t = %s",
                calibration_.performer.x(), calibration_.performer.y(), calibration_.performer.z(),
                seconds(sample.time - start_).c_str());
  messages_.push_back(text);
}

void StabilizedWands::waitForPerformer(const PerformerWait& wait) {
  // Said at once, then once per second of input: a waiting console is not flooded.
  double saidAt = -1.0;
  const bool live = !source_->length();
  HandSample held;  // the sample the set-up's hold began with (time < 0: none)
  held.time = -1.0;
  int counted = 0;  // the last number of the count said
  for (;;) {
    const HandSample& s = ahead_.back();
    if (confidentPose(s)) {
      if (wait.holdStill <= 0.0) break;
      const bool moved = held.time < 0.0 || (s.left.position - held.left.position).norm() > PerformerWait::kHeldStill ||
                         (s.right.position - held.right.position).norm() > PerformerWait::kHeldStill;
      if (moved) held = s;
      const double left = wait.holdStill - (s.time - held.time);
      if (left <= 0.0) break;
      if (const int count = static_cast<int>(std::ceil(3.0 * left / wait.holdStill)); count != counted) {
        wait.say("waiting for a performer: hold both hands forward and still: " + std::to_string(count));
        counted = count;
      }
    } else {
      held.time = -1.0;
      counted = 0;
      const bool one = s.left.measured || s.right.measured;
      const std::string why =
          bothMeasured(s) ? "both hands found, not surely yet (raise them in front of you)"
          : one ? std::string(s.left.measured ? "the left" : "the right") + " hand found, waiting for the other"
                : source_->whyNoHands();
      const double t = s.time - first_;
      if (saidAt < 0.0 || t - saidAt >= 1.0) {
        wait.say("waiting for a performer: " + why + " (" + seconds(t) + " of input)");
        saidAt = t;
      }
    }
    if (live && ahead_.size() > 1) ahead_.pop_front();            // a camera may wait for hours: keep the newest only
    if ((wait.cancelled && wait.cancelled()) || !fetch()) break;  // stopped, or the input ended or was lost
  }
  if (!confidentPose(ahead_.back())) {
    messages_.push_back(
        "warning: no performer found (no sample with both hands surely found); the run starts where the input does");
    start_ = ahead_.front().time;
    return;
  }
  // Run time 0 is the sample with both hands: the ones before it are dropped.
  ahead_.erase(ahead_.begin(), ahead_.end() - 1);
  start_ = ahead_.front().time;
  performerFound_ = start_ - first_;
  if (*performerFound_ > 0.0)  // an input with both hands from its first sample needs no word
    messages_.push_back("note: performer found after " + seconds(*performerFound_) +
                        " of input: both hands tracked; the film is made now");
  if (calibration_.autoPerformer) centreOnPerformer(ahead_.front());
}

std::optional<double> StabilizedWands::length() const {
  const std::optional<double> length = source_->length();
  if (!length) return std::nullopt;
  return std::max(*length - (start_ - first_), 0.0);
}

std::string StabilizedWands::describe() const { return describe_ + ", stabilized"; }

bool StabilizedWands::fetch() {
  if (finished_) return false;
  const double now = (ahead_.empty() ? lastFed_ : ahead_.back().time) - start_;
  try {
    std::optional<HandSample> s = source_->next();
    for (std::string& m : source_->takeMessages()) messages_.push_back(std::move(m));
    if (s) {
      ahead_.push_back(*s);
      return true;
    }
    messages_.push_back("note: input ended at t = " + seconds(now) + "; the wands hold still");
  } catch (const HandSourceLost& e) {
    messages_.push_back("warning: input lost at t = " + seconds(now) + ": " + e.what() + "; the wands hold still");
  }
  finished_ = true;
  return false;
}

void StabilizedWands::observeInterval(double dt) {
  if (!(dt > 0.0) || dt > 1.0) return;  // a gap, not the rate
  period_ = intervals_ == 0 ? dt : period_ + 0.1 * (dt - period_);
  ++intervals_;
  if (intervals_ >= 10 && !reportedSlow_ && period_ > 1.001 / kSlowRate) {  // 0.1%: timestamps round
    char text[200];
    std::snprintf(text, sizeof text,
                  "warning: the input delivers %.1f samples per second, below 25 (a Kinect gives 30): the wands "
                  "are interpolated between samples and follow less closely",
                  1.0 / period_);
    messages_.push_back(text);
    reportedSlow_ = true;
  }
}

void StabilizedWands::followPerformer(const HandSample& sample, double dt) {
  if (!calibration_.autoPerformer || !centreFromBody_ || !sample.body || !(dt > 0.0)) return;
  const Vec3d target = *sample.body + *centreFromBody_;
  Vec3d away = target - calibration_.performer;
  away.y() = 0.0;  // a squat is a gesture, not a walk
  const double distance = away.norm();
  movedFor_ = distance > kMovedDistance ? movedFor_ + dt : 0.0;
  if (!recentring_ && movedFor_ >= kMovedTime) {
    recentring_ = true;
    char text[160];
    std::snprintf(text, sizeof text, "note: the performer moved %.2f m at t = %s; the calibration follows them",
                  distance, seconds(sample.time - start_).c_str());
    messages_.push_back(text);
  }
  if (!recentring_) return;
  const double step = kRecentreSpeed * dt;
  calibration_.performer += distance <= step ? away : Vec3d(away * (step / distance));
  if (distance <= step) recentring_ = false;
}

void StabilizedWands::feed(const HandSample& sample) {
  followPerformer(sample, sample.time - lastFed_);
  stabilizer_->add(sample);
  lastFed_ = sample.time;
  latest_ = sample;
  for (int h = 0; h < 2; ++h) {
    const HandObservation& o = sample.hand(h == 0 ? Hand::Left : Hand::Right);
    if (o.measured) {
      if (reportedLost_[h])
        messages_.push_back(std::string("note: ") + handName(h) +
                            " hand seen again at t = " + seconds(sample.time - start_));
      reportedLost_[h] = false;
      lastMeasured_[h] = sample.time;
    } else if (!finished_ && !reportedLost_[h] && sample.time - lastMeasured_[h] > kLostHandAfter) {
      messages_.push_back(std::string("warning: ") + handName(h) +
                          " hand not seen since t = " + seconds(lastMeasured_[h] - start_) + "; its wand holds still");
      reportedLost_[h] = true;
    }
  }
}

double StabilizedWands::period() const { return std::max(source_->period(), kMinSamplePeriod); }

void StabilizedWands::holdUntil(double until, double period) {
  while (lastFed_ + period <= until) {
    HandSample hold = latest_;
    hold.time = lastFed_ + period;
    for (HandObservation* o : {&hold.left, &hold.right}) {
      o->measured = false;
      o->confidence *= std::exp(-period / 0.5);
    }
    feed(hold);
  }
}

void StabilizedWands::take(const HandSample& s, double period) {
  if (s.time - lastFed_ < kMinSamplePeriod) return;  // denser than the guard (or older): thinned, not fed
  observeInterval(s.time - lastFed_);
  if (s.time - lastFed_ > 3.0 * period) holdUntil(s.time - period, period);  // a gap: the wands rest through it
  feed(s);
  newestSample_ = s.time;
}

double StabilizedWands::wallClockTime(double t, double period) {
  while (source_->ready() && fetch()) {  // every sample that has arrived, none waited for
  }
  const double newest = ahead_.empty() ? newestSample_ : ahead_.back().time;
  if (!aligned_) {  // the first frame starts at the newest hands, not at those of when the input opened
    offset_ = std::max(0.0, newest - (start_ + t));
    aligned_ = true;
  } else if (const double behind = newest - (start_ + t + offset_) - period; behind > 0.0) {
    offset_ += std::min(behind, kCatchUp * std::max(t - lastT_, 0.0));  // a loop fallen behind catches up
  }
  lastT_ = t;
  // Never more than a period past the newest sample: a camera late with its hands (its thread starved of a core)
  // holds the input's time back, so that its samples are taken when they come instead of passed by and dropped.
  if (const double ahead = start_ + t + offset_ - (newest + period); ahead > 0.0) offset_ -= ahead;
  return start_ + t + offset_;
}

WandFrame StabilizedWands::at(double t) {
  // The observed period, not the nominal one: a camera delivering 7.5 frames per second is slow, not absent.
  const double period = std::max(period_, this->period());
  const bool wallClock = wallClock_ && source_->arrivedAt();
  const double T = wallClock ? wallClockTime(t, period) : start_ + t;
  while ((!ahead_.empty() || (!wallClock && fetch())) && ahead_.front().time <= T) {
    take(ahead_.front(), period);
    ahead_.pop_front();
  }
  if (T - lastFed_ > 3.0 * period || (finished_ && ahead_.empty())) holdUntil(T, period);

  WandFrame f;
  const WandPoint left = stabilizer_->at(Hand::Left, T), right = stabilizer_->at(Hand::Right, T);
  f.wands.leftPosition = calibration_.toWorld(left.position).cast<float>();
  f.wands.leftVelocity = calibration_.velocityToWorld(left.velocity).cast<float>();
  f.wands.rightPosition = calibration_.toWorld(right.position).cast<float>();
  f.wands.rightVelocity = calibration_.velocityToWorld(right.velocity).cast<float>();
  if (latest_.left.measured) f.leftHand = calibration_.toWorld(latest_.left.position).cast<float>();
  if (latest_.right.measured) f.rightHand = calibration_.toWorld(latest_.right.position).cast<float>();
  if (latest_.bodyPoints && latest_.bodyPoints != bodyInCamera_) {  // a new depth frame's body, into the world
    bodyInCamera_ = latest_.bodyPoints;
    auto world = std::make_shared<std::vector<Vec3>>();
    world->reserve(bodyInCamera_->size());
    for (const Eigen::Vector3f& p : *bodyInCamera_)
      world->push_back(calibration_.toWorld(p.cast<double>()).cast<float>());
    bodyInWorld_ = std::move(world);
    bodyTime_ = latest_.time - start_;
  }
  if (!latest_.bodyPoints) bodyInCamera_.reset(), bodyInWorld_.reset();  // nobody seen in the newest frame
  f.body = bodyInWorld_;
  f.bodyTime = bodyTime_;
  if (wallClock) {  // the newest sample arrived arrivedAgo; hands behind it (a loop catching up) are older still
    const double arrivedAgo =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - *source_->arrivedAt()).count();
    const double newest = ahead_.empty() ? newestSample_ : ahead_.back().time;
    f.handsAge = arrivedAgo + std::max(0.0, newest - T);
  }
  return f;
}

}  // namespace gb
