#include "model/wire_frame.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gb {

WandState interpolate(const WandState& a, const WandState& b, float t) {
  return {(1 - t) * a.leftPosition + t * b.leftPosition, (1 - t) * a.leftVelocity + t * b.leftVelocity,
          (1 - t) * a.rightPosition + t * b.rightPosition, (1 - t) * a.rightVelocity + t * b.rightVelocity};
}

float WireFrame::area() const {
  constexpr float pi = std::numbers::pi_v<float>;
  return kind == ToolKind::TwoWands ? 0.5f * pi * halfWidth * depth : pi * halfWidth * halfWidth;
}

float WireFrame::height() const { return kind == ToolKind::TwoWands ? depth : 2.0f * halfWidth; }

Vec3 wirePoint(const WireFrame& f, float u) {
  constexpr float pi = std::numbers::pi_v<float>;
  if (f.kind == ToolKind::TwoWands && u < 1.0f) return f.center + (2.0f * u - 1.0f) * f.halfWidth * f.axis;
  // Along an arc the direction from the centre is the spherical linear interpolation between the
  // orthonormal in-plane axes: slerp(axis, down, t) = cos(t pi/2) axis + sin(t pi/2) down (Section 7).
  const float phi = f.kind == ToolKind::TwoWands ? (u - 1.0f) * pi : 2.0f * pi * u;
  return f.center + f.halfWidth * std::cos(phi) * f.axis + f.depth * std::sin(phi) * f.down;
}

float hangingStringLength(float a, float b) {
  constexpr float pi = std::numbers::pi_v<float>;
  return 0.5f * pi * (3.0f * (a + b) - std::sqrt((3.0f * a + b) * (a + 3.0f * b)));
}

float hangingDepth(float halfWidth, float stringLength) {
  // The length grows monotonically with depth; bisection to 1e-6 relative. A string too short for the
  // tip separation is taut: depth 0, the film degenerates to a line (the pinch-off case).
  if (stringLength <= hangingStringLength(halfWidth, 0.0f)) return 0.0f;
  float lo = 0.0f, hi = stringLength;
  for (int it = 0; it < 60 && hi - lo > 1e-6f * stringLength; ++it) {
    const float mid = 0.5f * (lo + hi);
    (hangingStringLength(halfWidth, mid) < stringLength ? lo : hi) = mid;
  }
  return 0.5f * (lo + hi);
}

namespace {

// Unit vector perpendicular to axis, as close as possible to preferred; a fixed world axis when preferred
// is (nearly) parallel to axis, so the frame never degenerates.
Vec3 perpendicularTowards(const Vec3& axis, const Vec3& preferred) {
  Vec3 d = preferred - preferred.dot(axis) * axis;
  if (d.norm() > 1e-3f * preferred.norm() && preferred.norm() > 0) return d.normalized();
  const Vec3 fallback = std::abs(axis.z()) < 0.9f ? Vec3::UnitZ() : Vec3::UnitX();
  return (fallback - fallback.dot(axis) * axis).normalized();
}

}  // namespace

Vec3 spanAxis(const WandState& wands) {
  const Vec3 span = wands.rightPosition - wands.leftPosition;
  const float width = span.norm();
  return width > 1e-6f ? Vec3(span / width) : Vec3(Vec3::UnitX());
}

Vec3 swingLoop(const Vec3& previousDown, const Vec3& axis, const Vec3& gravity, float maxTurn) {
  const Vec3 current = perpendicularTowards(axis, previousDown);
  const Vec3 pull = gravity - gravity.dot(axis) * axis;  // gravity's part that turns the loop about the span
  if (!(pull.norm() > 1e-3f * gravity.norm())) return current;
  const Vec3 target = pull.normalized();
  const float angle = std::atan2(current.cross(target).dot(axis), current.dot(target));  // signed, about axis
  if (std::abs(angle) <= maxTurn) return target;
  const float turn = std::copysign(maxTurn, angle);
  return (std::cos(turn) * current + std::sin(turn) * axis.cross(current)).normalized();
}

WireFrame makeWireFrame(const WandTool& tool, const WandState& wands, float stringLength, const Vec3& hangTowards) {
  WireFrame f;
  f.kind = tool.kind;
  const Vec3 down = hangTowards.norm() > 0 ? Vec3(hangTowards.normalized()) : Vec3(-Vec3::UnitY());
  if (tool.kind == ToolKind::Ring) {
    // The ring faces the world z axis and is centred on the right hand.
    f.center = wands.rightPosition;
    f.axis = perpendicularTowards(Vec3::UnitZ(), Vec3::UnitX());
    f.down = perpendicularTowards(Vec3::UnitZ(), down);
    f.halfWidth = f.depth = tool.ringRadius;
    return f;
  }
  const float width = (wands.rightPosition - wands.leftPosition).norm();
  f.center = 0.5f * (wands.leftPosition + wands.rightPosition);
  f.axis = spanAxis(wands);
  f.down = perpendicularTowards(f.axis, down);
  f.halfWidth = 0.5f * width;
  f.depth = hangingDepth(f.halfWidth, stringLength);
  return f;
}

std::vector<float> evenlySpacedParameters(const WireFrame& f, float u0, float u1, int n) {
  constexpr int samples = 2048;
  std::vector<float> length(samples + 1, 0.0f);
  Vec3 prev = wirePoint(f, u0);
  for (int k = 1; k <= samples; ++k) {
    const Vec3 p = wirePoint(f, u0 + (u1 - u0) * static_cast<float>(k) / samples);
    length[k] = length[k - 1] + (p - prev).norm();
    prev = p;
  }
  std::vector<float> us;
  for (int m = 0; m < n; ++m) {
    const float target = length[samples] * static_cast<float>(m) / static_cast<float>(n);
    const auto it = std::lower_bound(length.begin(), length.end(), target);
    const int k = std::max(1, static_cast<int>(it - length.begin()));
    const float span = length[k] - length[k - 1];
    const float w = span > 0 ? (target - length[k - 1]) / span : 0.0f;
    us.push_back(u0 + (u1 - u0) * (static_cast<float>(k - 1) + w) / samples);
  }
  return us;
}

float frameArcLength(const WireFrame& f, float u0, float u1) {
  constexpr int samples = 2048;
  float len = 0.0f;
  Vec3 prev = wirePoint(f, u0);
  for (int k = 1; k <= samples; ++k) {
    const Vec3 p = wirePoint(f, u0 + (u1 - u0) * static_cast<float>(k) / samples);
    len += (p - prev).norm();
    prev = p;
  }
  return len;
}

std::vector<float> wireParameters(const WireFrame& f, float spacing) {
  auto segments = [&](float len) { return std::max(3, static_cast<int>(std::lround(len / spacing))); };
  if (f.kind == ToolKind::Ring) return evenlySpacedParameters(f, 0.0f, 1.0f, segments(frameArcLength(f, 0.0f, 1.0f)));
  std::vector<float> us = evenlySpacedParameters(f, 0.0f, 1.0f, segments(frameArcLength(f, 0.0f, 1.0f)));
  const std::vector<float> bottom = evenlySpacedParameters(f, 1.0f, 2.0f, segments(frameArcLength(f, 1.0f, 2.0f)));
  us.insert(us.end(), bottom.begin(), bottom.end());
  return us;
}

}  // namespace gb
