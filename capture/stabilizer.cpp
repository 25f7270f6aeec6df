#include "stabilizer.h"

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

HandStabilizer::HandStabilizer(const StabilizerOptions& options, const Vec3d& rest) : o_(options), rest_(rest) {
  if (o_.velocitySpan < 1) throw std::invalid_argument("stabilizer velocitySpan must be at least 1");
  if (o_.kind == StabilizerKind::BSpline)
    smoother_ = std::make_unique<BSplineSmoother>(o_.velocitySpan, o_.period);
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
    t_ = t;
    confidence_ = hand.confidence;
    started_ = true;
    return;
  }
  const double h = t - t_;
  if (h <= 0.0) return;  // a sample not after the previous one adds nothing

  // Gate: the next control point is the measurement, unless it is an outlier (then the prediction) or the
  // hand was not measured (then the last control point again: the hold). The prediction carries the last
  // control point on with the smoothed velocity, which noise and outliers barely move.
  const Vec3d predicted = control_ + h * reference_.velocity;
  Vec3d control = control_;
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
      smoother_->reset(t - h, hand.position);
      control = hand.position;
      outliers_ = 0;
    }
  }
  control_ = control;

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
  confidence_ = hand.confidence;
}

WandPoint HandStabilizer::at(double t) const {
  const double ahead = t - t_;
  if (ahead <= 0.0) return wand_;
  if (ahead > o_.extrapolation) return {wand_.position + o_.extrapolation * wand_.velocity, Vec3d::Zero()};
  return {wand_.position + ahead * wand_.velocity, wand_.velocity};
}

Stabilizer::Stabilizer(const StabilizerOptions& options, const Vec3d& restLeft, const Vec3d& restRight)
    : hands_{HandStabilizer(options, restLeft), HandStabilizer(options, restRight)} {}

void Stabilizer::add(const HandSample& sample) {
  hands_[0].add(sample.time, sample.left);
  hands_[1].add(sample.time, sample.right);
}

}  // namespace gb
