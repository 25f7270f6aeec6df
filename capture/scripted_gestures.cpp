#include "scripted_gestures.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

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

}  // namespace

WandState gestureAt(Gesture gesture, const GestureOptions& o, double t) {
  WandState w;
  w.leftPosition = Vec3(-0.5f * o.tipSeparation, o.height, 0.0f);
  w.rightPosition = Vec3(0.5f * o.tipSeparation, o.height, 0.0f);
  switch (gesture) {
    case Gesture::Straight: {
      double distance = 0, speed = 0;
      strokeAt(o, t - o.start, distance, speed);
      const Vec3 offset(0.0f, 0.0f, static_cast<float>(distance));
      const Vec3 velocity(0.0f, 0.0f, static_cast<float>(speed));
      w.leftPosition += offset;
      w.rightPosition += offset;
      w.leftVelocity = w.rightVelocity = velocity;
      break;
    }
  }
  return w;
}

Gesture gestureFromName(const std::string& name) {
  if (name == "straight") return Gesture::Straight;
  throw std::invalid_argument("unknown gesture '" + name + "' (choices: straight)");
}

std::vector<std::string> gestureNames() { return {"straight"}; }

}  // namespace gb
