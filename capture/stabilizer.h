#pragma once
// From tracked hands to smooth wands (Sections 4.2-4.3), in camera space, one hand at a time:
//
//   gate        a measured position far from where the hand was heading is an outlier and replaced by that
//               prediction; outlierRun + 1 of them in a row are the hand really elsewhere: the smoothed
//               trajectory restarts there and the wand glides over; a hand not measured repeats its last
//               control point, so its wand comes smoothly to rest there (hold);
//   B-spline    (the paper) the control points are appended to a uniform cubic B-spline, evaluated
//               sequentially at its newest complete knot: s_n = (P_{n-2} + 4 P_{n-1} + P_n) / 6;
//               the hand velocity is the finite difference of s over velocitySpan samples, appended as the
//               control points of a second cubic B-spline and smoothed the same way: v_hand;
//   One Euro    (beyond the paper) Casiez et al.'s speed-adaptive low-pass filter of the control points;
//   Eq. (1)     x_wand^{t+h} = x_wand^t + h v_hand^t, with a speed and an acceleration limit, and a drift
//               correction towards the smoothed trajectory (time constant driftTime) that vanishes when no
//               limit acts: then x_wand is exactly the smoothed trajectory, because the B-spline of the
//               differences is the difference of the B-spline.
//
// Any input rate: the gated control points are interpolated onto knots at most 1/30 s apart (linearly between
// samples), and the splines and Eq. (1) run on the knots, so a 15 Hz input is no later than a 30 Hz one.
//
// On a straight line at constant speed the B-spline wand reproduces the hand exactly, 2 + (velocitySpan - 1)/2
// knots late (3 knots, 0.1 s, by default). docs/capture.md gives the jitter and lag of both.

#include <array>
#include <deque>
#include <memory>
#include <string>

#include "capture/hand_source.h"

namespace gb {

enum class StabilizerKind { BSpline, OneEuro };

struct OneEuroOptions {
  double minCutoff = 0.6;         // Hz, cutoff when the hand is still
  double beta = 1.5;              // Hz per m/s: how fast the cutoff rises with speed
  double derivativeCutoff = 1.0;  // Hz, low-pass on the speed estimate
};

struct StabilizerOptions {
  StabilizerKind kind = StabilizerKind::BSpline;
  int velocitySpan = 3;           // samples between the positions a finite-difference velocity uses (>= 1)
  double outlierDistance = 0.15;  // m: a measurement this far from the prediction is an outlier (0: no gate)
  int outlierRun = 3;             // consecutive outliers taken as real motion
  double maxSpeed = 4.0;          // m/s: the wand never moves faster (camera space)
  double maxAcceleration = 40.0;  // m/s^2: nor changes its velocity faster
  // The wand tips in the world (StabilizedWands lowers the two limits above to these over the calibration's reach):
  // a film drawn by tips faster than a few metres a second tears at the wire or slams into itself, and a performer's
  // hands, times the reach, reach 6-8 m/s (docs/capture.md, "Films under real hands").
  double tipSpeed = 3.0;          // m/s
  double tipAcceleration = 20.0;  // m/s^2
  double driftTime = 0.3;         // s: return to the smoothed trajectory after a limit acted
  double extrapolation = 0.1;     // s: how far past the newest knot at() carries a wand on by Eq. (1) (at least
                                  //   1.5 input periods, so that a slow input never stands still between samples)
  double period = 1.0 / 30.0;     // s: the input's nominal sample period; the knots are this far apart, at most
                                  //   1/30 s (a slower input is interpolated onto 30 knots per second)
  OneEuroOptions oneEuro;
};

StabilizerKind stabilizerFromName(const std::string& name);  // "bspline" or "one-euro"; throws naming both

struct WandPoint {
  Vec3d position = Vec3d::Zero();
  Vec3d velocity = Vec3d::Zero();
};

// The smoothed trajectory of one hand: per control point, the reference position r_n and velocity w_n
// (in the ideal case h w_n = r_n - r_{n-1}, so Eq. (1) reproduces r_n).
class TrajectorySmoother {
 public:
  virtual ~TrajectorySmoother() = default;
  virtual void reset(double t, const Vec3d& p) = 0;
  virtual WandPoint add(double t, const Vec3d& controlPoint) = 0;
};

class BSplineSmoother : public TrajectorySmoother {
 public:
  explicit BSplineSmoother(int velocitySpan, double period) : span_(velocitySpan), period_(period) {}
  void reset(double t, const Vec3d& p) override;
  WandPoint add(double t, const Vec3d& controlPoint) override;

 private:
  int span_;
  double period_;
  std::deque<Vec3d> controls_;    // last 3 control points
  std::deque<double> times_;      // and their times
  std::deque<Vec3d> smoothed_;    // s, last span + 1 values
  std::deque<double> knots_;      // the time of each s (its middle control point)
  std::deque<Vec3d> velocities_;  // velocity control points, last 3
  std::deque<Vec3d> means_;       // moving means of s over span values, last 3 (the reference's control points)
};

class OneEuroSmoother : public TrajectorySmoother {
 public:
  explicit OneEuroSmoother(const OneEuroOptions& o) : o_(o) {}
  void reset(double t, const Vec3d& p) override;
  WandPoint add(double t, const Vec3d& controlPoint) override;

 private:
  OneEuroOptions o_;
  Vec3d x_ = Vec3d::Zero(), dx_ = Vec3d::Zero();
  double t_ = 0.0;
};

// One hand: gate, smoother, Eq. (1).
class HandStabilizer {
 public:
  HandStabilizer(const StabilizerOptions& options, const Vec3d& rest);
  void add(double t, const HandObservation& hand);
  [[nodiscard]] WandPoint at(double t) const;  // t at or after the newest sample
  [[nodiscard]] double confidence() const { return confidence_; }

 private:
  void advance(double t, const Vec3d& control);  // one knot: smoother, Eq. (1), limits
  StabilizerOptions o_;
  std::unique_ptr<TrajectorySmoother> smoother_;
  bool started_ = false;
  double knotPeriod_;       // the splines' knot spacing: the input's period, at most 1/30 s
  double inputPeriod_;      // how often samples have been coming (s, smoothed)
  double t_ = 0.0;          // the newest knot, where wand_ is
  double inputTime_ = 0.0;  // the newest sample
  double nextKnot_ = 0.0;
  double confidence_ = 0.0;
  Vec3d rest_;
  Vec3d control_ = Vec3d::Zero();  // the newest control point
  WandPoint reference_;            // the smoothed trajectory at the newest control point
  int outliers_ = 0;               // outliers in a row
  WandPoint wand_;
};

// Both hands.
class Stabilizer {
 public:
  Stabilizer(const StabilizerOptions& options, const Vec3d& restLeft, const Vec3d& restRight);
  void add(const HandSample& sample);  // samples in time order
  [[nodiscard]] WandPoint at(Hand hand, double t) const { return hands_[static_cast<int>(hand)].at(t); }
  [[nodiscard]] double confidence(Hand hand) const { return hands_[static_cast<int>(hand)].confidence(); }

 private:
  std::array<HandStabilizer, 2> hands_;
};

}  // namespace gb
