#include "capture/stabilizer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace gb {

StabilizerKind stabilizerFromName(const std::string& name) {
  if (name == "bspline") return StabilizerKind::BSpline;
  if (name == "one-euro") return StabilizerKind::OneEuro;
  throw std::invalid_argument("unknown stabilizer '" + name + "' (choices: bspline, one-euro)");
}

namespace {

// The uniform cubic B-spline at the knot between its last three control points.
Vec3d knotValue(const std::deque<Vec3d>& p) { return (p[0] + 4.0 * p[1] + p[2]) / 6.0; }

constexpr double kKnotPeriod = 1.0 / 30.0;  // s: the splines' knots, at most this far apart (the Kinect's rate)

template <typename T>
void push(std::deque<T>& q, const T& value) {
  q.pop_front();
  q.push_back(value);
}

}  // namespace

void BSplineSmoother::reset(double t, const Vec3d& p) {
  // Clamped start: the curve begins at the first point, as if the hand had rested there before.
  controls_.assign(3, p);
  times_ = {t - 2 * period_, t - period_, t};
  smoothed_.assign(span_ + 1, p);
  knots_.clear();
  for (int j = span_; j >= 0; --j) knots_.push_back(t - period_ * (j + 1));
  velocities_.assign(3, Vec3d::Zero());
  means_.assign(3, p);
}

WandPoint BSplineSmoother::add(double t, const Vec3d& controlPoint) {
  push(controls_, controlPoint);
  push(times_, t);
  push(smoothed_, knotValue(controls_));  // s_n: the trajectory, one sample behind the newest control point
  push(knots_, times_[1]);
  // Finite difference over span samples (Section 4.3), a control point of the velocity's B-spline.
  const double dt = knots_.back() - knots_.front();
  push(velocities_, dt > 0.0 ? Vec3d((smoothed_.back() - smoothed_.front()) / dt) : Vec3d::Zero());
  // The position the smoothed velocity integrates to: the same B-spline over the moving means of s.
  Vec3d mean = Vec3d::Zero();
  for (size_t i = 1; i < smoothed_.size(); ++i) mean += smoothed_[i];
  push(means_, Vec3d(mean / span_));
  return {knotValue(means_), knotValue(velocities_)};
}

void OneEuroSmoother::reset(double t, const Vec3d& p) {
  x_ = p;
  dx_ = Vec3d::Zero();
  t_ = t;
}

WandPoint OneEuroSmoother::add(double t, const Vec3d& controlPoint) {
  const double dt = t - t_;
  if (dt <= 0.0) return {x_, Vec3d::Zero()};
  // Casiez, Roussel and Vogel, "1 Euro filter" (CHI 2012): an exponential low-pass whose cutoff rises with the
  // (itself low-passed) speed, smoothing a still hand hard and a moving one little.
  auto alpha = [dt](double cutoff) { return 1.0 / (1.0 + 1.0 / (2.0 * std::numbers::pi * cutoff * dt)); };
  dx_ += alpha(o_.derivativeCutoff) * ((controlPoint - x_) / dt - dx_);
  const Vec3d next = x_ + alpha(o_.minCutoff + o_.beta * dx_.norm()) * (controlPoint - x_);
  const Vec3d velocity = (next - x_) / dt;
  x_ = next;
  t_ = t;
  return {x_, velocity};
}

HandStabilizer::HandStabilizer(const StabilizerOptions& options, const Vec3d& rest)
    : o_(options), knotPeriod_(std::min(options.period, kKnotPeriod)), inputPeriod_(options.period), rest_(rest) {
  if (o_.velocitySpan < 1) throw std::invalid_argument("stabilizer velocitySpan must be at least 1");
  if (!(o_.period > 0.0)) throw std::invalid_argument("stabilizer period must be positive");
  if (o_.kind == StabilizerKind::BSpline)
    smoother_ = std::make_unique<BSplineSmoother>(o_.velocitySpan, knotPeriod_);
  else
    smoother_ = std::make_unique<OneEuroSmoother>(o_.oneEuro);
}

void HandStabilizer::add(double t, const HandObservation& hand) {
  if (!started_) {
    const Vec3d p = hand.seen() ? hand.position : rest_;
    smoother_->reset(t, p);
    control_ = p;
    reference_ = {p, Vec3d::Zero()};
    wand_ = {p, Vec3d::Zero()};
    t_ = inputTime_ = t;
    nextKnot_ = t + knotPeriod_;
    confidence_ = hand.confidence;
    started_ = true;
    return;
  }
  const double h = t - inputTime_;
  if (h <= 0.0) return;                                     // a sample not after the previous one adds nothing
  inputPeriod_ += 0.2 * (std::min(h, 1.0) - inputPeriod_);  // how often samples come, for the extrapolation

  // Gate: the next control point is the measurement, unless it is an outlier (then the prediction) or the
  // hand was not measured (then the last control point again: the hold). The prediction carries the last
  // control point on with the smoothed velocity, which noise and outliers barely move.
  const Vec3d predicted = control_ + h * reference_.velocity;
  Vec3d from = control_, control = control_;
  if (hand.measured) {
    if (o_.outlierDistance <= 0.0 || (hand.position - predicted).norm() <= o_.outlierDistance) {
      control = hand.position;
      outliers_ = 0;
    } else if (outliers_ < o_.outlierRun) {
      control = predicted;
      ++outliers_;
    } else {
      // A run of outliers is the hand really somewhere else (found again, or re-detected): the smoothed
      // trajectory starts over there and the wand glides across, within its limits, by the drift correction.
      smoother_->reset(t_, hand.position);
      from = control = hand.position;
      outliers_ = 0;
    }
  }
  control_ = control;
  // Onto the knots: the splines run at a fixed rate whatever the input's, so that a slow input is not a slow,
  // late spline. Control points between two samples lie on the straight line between them.
  while (nextKnot_ <= t + 1e-9) {
    const double s = std::clamp((nextKnot_ - inputTime_) / h, 0.0, 1.0);
    advance(nextKnot_, from + s * (control - from));
    nextKnot_ += knotPeriod_;
  }
  inputTime_ = t;
  confidence_ = hand.confidence;
}

void HandStabilizer::advance(double t, const Vec3d& control) {
  const double h = t - t_;
  // Eq. (1) with the smoothed hand velocity, the drift correction, and the limits.
  reference_ = smoother_->add(t, control);
  const Vec3d carried = wand_.position + h * reference_.velocity;
  const double pull = 1.0 - std::exp(-h / o_.driftTime);
  Vec3d velocity = reference_.velocity + pull * (reference_.position - carried) / h;
  const Vec3d change = velocity - wand_.velocity;
  if (change.norm() > o_.maxAcceleration * h)
    velocity = wand_.velocity + change * (o_.maxAcceleration * h / change.norm());
  if (velocity.norm() > o_.maxSpeed) velocity *= o_.maxSpeed / velocity.norm();
  wand_.position += h * velocity;
  wand_.velocity = velocity;
  t_ = t;
}

WandPoint HandStabilizer::at(double t) const {
  // Carried on by Eq. (1) up to the next sample's knots, however slow the input (no standing still between
  // samples), and no further than the extrapolation limit past that.
  const double limit = std::max(o_.extrapolation, 1.5 * inputPeriod_);
  const double ahead = t - t_;
  if (ahead <= 0.0) return wand_;
  if (ahead > limit) return {wand_.position + limit * wand_.velocity, Vec3d::Zero()};
  return {wand_.position + ahead * wand_.velocity, wand_.velocity};
}

Stabilizer::Stabilizer(const StabilizerOptions& options, const Vec3d& restLeft, const Vec3d& restRight)
    : hands_{HandStabilizer(options, restLeft), HandStabilizer(options, restRight)} {}

void Stabilizer::add(const HandSample& sample) {
  hands_[0].add(sample.time, sample.left);
  hands_[1].add(sample.time, sample.right);
}

}  // namespace gb
