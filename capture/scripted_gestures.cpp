#include "capture/scripted_gestures.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace gb {

namespace {

// Distance travelled and speed of the sin^2 stroke at time tau into it (analytic integral of the speed).
void strokeAt(const GestureOptions& o, double tau, double& distance, double& speed) {
  const double T = o.duration, pi = std::numbers::pi;
  const double clamped = std::clamp(tau, 0.0, T);
  distance = o.speed * (clamped / 2.0 - T / (4.0 * pi) * std::sin(2.0 * pi * clamped / T));
  const double s = std::sin(pi * clamped / T);
  speed = (tau > 0 && tau < T) ? o.speed * s * s : 0.0;
}

// The giant bubble's stroke: speed rises as sin^2 over the first kGiantRise of it, holds, and falls as sin^2 over
// the last kGiantFall, so the wands are still at full speed (the bag still full of their air) when they close;
// closed, they slow down and lift away (kGiantLift) so the bubble flies on ahead of them.
constexpr double kGiantRise = 0.35, kGiantCloseFrom = 0.45, kGiantCloseTo = 0.72, kGiantFall = 1.0 - kGiantCloseTo;
constexpr double kGiantLift = 0.4;  // m

void giantStrokeAt(const GestureOptions& o, double tau, double& distance, double& speed) {
  const double T = o.duration, pi = std::numbers::pi, t = std::clamp(tau, 0.0, T);
  const double rise = kGiantRise * T, fall = kGiantFall * T, holdEnd = T - fall;
  // Distance covered by a sin^2 ramp of length r after time x into it: S (x/2 - r/(2 pi) sin(pi x / r)).
  auto ramp = [&](double x, double r) { return o.speed * (x / 2.0 - r / (2.0 * pi) * std::sin(pi * x / r)); };
  if (t < rise) {
    distance = ramp(t, rise);
    speed = o.speed * std::pow(std::sin(pi * t / (2.0 * rise)), 2);
  } else if (t < holdEnd) {
    distance = ramp(rise, rise) + o.speed * (t - rise);
    speed = o.speed;
  } else {  // the falling half-ramp, mirrored: full speed at holdEnd, still at T
    const double x = t - holdEnd;
    distance = ramp(rise, rise) + o.speed * (holdEnd - rise) + ramp(fall, fall) - ramp(fall - x, fall);
    speed = o.speed * std::pow(std::sin(pi * (fall - x) / (2.0 * fall)), 2);
  }
  if (!(tau > 0 && tau < T)) speed = 0.0;
}

}  // namespace

struct HandOffsets {
  Vec3 left = Vec3::Zero();
  Vec3 right = Vec3::Zero();
};

// Extra motion of the left and right tips on top of the forward stroke (m), for the non-straight gestures.
HandOffsets extraMotion(Gesture gesture, const GestureOptions& o, double tau) {
  const double T = o.duration, pi = std::numbers::pi, u = std::clamp(tau, 0.0, T) / T;
  const double envelope = std::sin(pi * u) * std::sin(pi * u);
  // A circle of the given radius in the x-y plane, starting at the rest position.
  auto circle = [&](double turns, double radius) {
    const double a = 2.0 * pi * turns * u;
    return Vec3(static_cast<float>(radius * (std::cos(a) - 1.0) * envelope),
                static_cast<float>(radius * std::sin(a) * envelope), 0.0f);
  };
  HandOffsets h;
  switch (gesture) {
    case Gesture::Straight:
      break;
    case Gesture::CircleLeft:
      h.left = circle(2.0, 0.15);
      break;
    case Gesture::Circles:  // mirrored: both hands circle outwards
      h.left = circle(2.0, 0.15);
      h.right = -circle(2.0, 0.15);
      break;
    case Gesture::Twisted: {
      // Redirections coming faster and wider: the swing's frequency grows from 1 to 3 Hz over the stroke.
      const double phase = 2.0 * pi * (u + u * u) * T, amplitude = envelope * (0.5 + u);
      h.left = Vec3(0.0f, static_cast<float>(0.25 * std::sin(phase) * amplitude),
                    static_cast<float>(0.2 * std::sin(1.3 * phase) * amplitude));
      h.right = -h.left;
      break;
    }
    case Gesture::UpDown:
      h.left = h.right = Vec3(0.0f, static_cast<float>(0.25 * std::sin(2.0 * pi * 1.5 * u * T) * envelope), 0.0f);
      break;
    case Gesture::Rising:  // from 0.6 m below up to the tip height
      h.left = h.right = Vec3(0.0f, static_cast<float>(-0.6 * (1.0 - u)), 0.0f);
      break;
    case Gesture::Giant: {
      // A giant bubble is blown and let go: at full speed (giantStrokeAt) the tips come together to kClosedGap,
      // well inside Params::pinchDistance, so the bag behind them pinches off into a free bubble.
      constexpr double kClosedGap = 0.04;
      const double closing = std::clamp((u - kGiantCloseFrom) / (kGiantCloseTo - kGiantCloseFrom), 0.0, 1.0);
      const double eased = closing * closing * (3.0 - 2.0 * closing);  // smoothstep: no jerk at either end
      const double lifting = std::clamp((u - kGiantCloseTo) / kGiantFall, 0.0, 1.0);
      const auto lift = static_cast<float>(kGiantLift * lifting * lifting * (3.0 - 2.0 * lifting));
      h.left = Vec3(static_cast<float>(0.5 * (o.tipSeparation - kClosedGap) * eased), lift, 0.0f);
      h.right = Vec3(-h.left.x(), lift, 0.0f);
      break;
    }
  }
  return h;
}

WandState gestureAt(Gesture gesture, const GestureOptions& o, double t) {
  WandState w;
  w.leftPosition = Vec3(-0.5f * o.tipSeparation, o.height, 0.0f);
  w.rightPosition = Vec3(0.5f * o.tipSeparation, o.height, 0.0f);
  double distance = 0, speed = 0;
  if (gesture == Gesture::Giant)
    giantStrokeAt(o, t - o.start, distance, speed);
  else
    strokeAt(o, t - o.start, distance, speed);
  const Vec3 offset(0.0f, 0.0f, static_cast<float>(distance));
  const Vec3 velocity(0.0f, 0.0f, static_cast<float>(speed));
  w.leftPosition += offset;
  w.rightPosition += offset;
  w.leftVelocity = w.rightVelocity = velocity;
  if (gesture == Gesture::Straight) return w;
  constexpr double h = 1e-4;
  const HandOffsets now = extraMotion(gesture, o, t - o.start);
  const HandOffsets ahead = extraMotion(gesture, o, t - o.start + h), behind = extraMotion(gesture, o, t - o.start - h);
  w.leftPosition += now.left;
  w.rightPosition += now.right;
  w.leftVelocity += (ahead.left - behind.left) / static_cast<float>(2 * h);
  w.rightVelocity += (ahead.right - behind.right) / static_cast<float>(2 * h);
  return w;
}

namespace {
const std::pair<const char*, Gesture> kGestures[] = {
    {"straight", Gesture::Straight}, {"circle-left", Gesture::CircleLeft}, {"circles", Gesture::Circles},
    {"twisted", Gesture::Twisted},   {"up-down", Gesture::UpDown},         {"rising", Gesture::Rising},
    {"giant", Gesture::Giant}};
}  // namespace

Gesture gestureFromName(const std::string& name) {
  for (const auto& [n, g] : kGestures)
    if (name == n) return g;
  std::string choices;
  for (const auto& [n, g] : kGestures) choices += std::string(choices.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown gesture '" + name + "' (choices: " + choices + ")");
}

std::vector<std::string> gestureNames() {
  std::vector<std::string> names;
  for (const auto& [n, g] : kGestures) names.push_back(n);
  return names;
}

}  // namespace gb
