#include "scripted_gestures.h"

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
  }
  return h;
}

WandState gestureAt(Gesture gesture, const GestureOptions& o, double t) {
  WandState w;
  w.leftPosition = Vec3(-0.5f * o.tipSeparation, o.height, 0.0f);
  w.rightPosition = Vec3(0.5f * o.tipSeparation, o.height, 0.0f);
  double distance = 0, speed = 0;
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
    {"twisted", Gesture::Twisted},   {"up-down", Gesture::UpDown},         {"rising", Gesture::Rising}};
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
