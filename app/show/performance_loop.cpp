#include "app/show/performance_loop.h"

#include <algorithm>

namespace gb {

PerformanceLoop::Action PerformanceLoop::next(double t, bool performanceOver, bool wandsFree, double emptySince) {
  const bool emptyLongEnough = emptySince >= 0 && t - emptySince >= autoDip_;
  switch (phase_) {
    case Phase::Playing:
      if (autoDip_ < 0) return Action::Play;
      return (performanceOver && wandsFree) || emptyLongEnough ? Action::StartReturn : Action::Play;
    case Phase::Returning:
      if (t < end_) return Action::Return;
      phase_ = Phase::AtStart;
      [[fallthrough]];
    case Phase::AtStart:
      if (!wandsFree) {  // a film dipped by hand during the return: it is blown from the start
        phase_ = Phase::Playing;
        return Action::StartPlaying;
      }
      if (emptyLongEnough) {
        phase_ = Phase::Playing;
        return Action::DipAndPlay;
      }
      return Action::Return;  // at the start pose, waiting for the stage's pause to pass
  }
  return Action::Play;
}

void PerformanceLoop::startReturn(double t, const WandState& from, const WandState& to) {
  const double way =
      std::max((to.leftPosition - from.leftPosition).norm(), (to.rightPosition - from.rightPosition).norm());
  begin_ = t;
  end_ = t + std::max(kShortestReturn, way / kReturnSpeed);
  from_ = from;
  to_ = to;
  phase_ = Phase::Returning;
}

WandState PerformanceLoop::returnWands(double t) const {
  const double u = std::clamp((t - begin_) / std::max(end_ - begin_, 1e-9), 0.0, 1.0);
  const auto s = static_cast<float>(u * u * (3.0 - 2.0 * u));                                 // smoothstep
  const auto rate = static_cast<float>(6.0 * u * (1.0 - u) / std::max(end_ - begin_, 1e-9));  // ds/dt
  WandState w;
  w.leftPosition = from_.leftPosition + s * (to_.leftPosition - from_.leftPosition);
  w.rightPosition = from_.rightPosition + s * (to_.rightPosition - from_.rightPosition);
  w.leftVelocity = rate * (to_.leftPosition - from_.leftPosition);
  w.rightVelocity = rate * (to_.rightPosition - from_.rightPosition);
  return w;
}

}  // namespace gb
