#pragma once
// The wire frame that holds the film (Figure 1): two wand tips joined by a loop of string, or a single ring.
// A boundary particle keeps a fixed frame coordinate u and is placed at wirePoint(frame, u) every step, so
// the film's edge follows the wands.

#include <vector>

#include "model/state.h"

namespace gb {

// Wand tips in world space, the output of capture/'s stabilizer (Section 4) and the input of the model.
struct WandState {
  Vec3 leftPosition = Vec3::Zero();
  Vec3 leftVelocity = Vec3::Zero();
  Vec3 rightPosition = Vec3::Zero();
  Vec3 rightVelocity = Vec3::Zero();
};

// Linear interpolation of two wand states, used to feed substeps between input frames.
WandState interpolate(const WandState& a, const WandState& b, float t);

enum class ToolKind : int { TwoWands = 0, Ring = 1 };

// The bubble tool a performer holds (options struct; defaults are the built-in tool sizes).
struct WandTool {
  ToolKind kind = ToolKind::TwoWands;
  float loopDepth = 0.8f;    // two wands: how far the string hangs below the tips after a full dip (m)
  float ringRadius = 0.35f;  // single ring wand: ring radius (m); the ring is centred on the right hand
};

// The frame at one instant. Two wands: a straight top string from the left tip (u = 0) to the right tip
// (u = 1), then the hanging bottom string as a half ellipse from the right tip back to the left (u in [1, 2)).
// Ring: a circle, u in [0, 1). axis and down span the frame's plane; axis x down is the film's normal.
struct WireFrame {
  ToolKind kind = ToolKind::TwoWands;
  Vec3 center = Vec3::Zero();
  Vec3 axis = Vec3::UnitX();   // left tip -> right tip (ring: first in-plane axis)
  Vec3 down = -Vec3::UnitY();  // in-plane direction the loop hangs towards
  float halfWidth = 0.5f;      // half the tip separation (ring: radius)
  float depth = 0.5f;          // how far the bottom string hangs below the tips (ring: radius)
  [[nodiscard]] float parameterEnd() const { return kind == ToolKind::TwoWands ? 2.0f : 1.0f; }
  // Area enclosed by the frame (Area_wm of Eq. 6) and its height (H_wire of Eq. 6).
  [[nodiscard]] float area() const;
  [[nodiscard]] float height() const;
};

// Position on the frame of the boundary particle with frame coordinate u.
Vec3 wirePoint(const WireFrame& frame, float u);

// Length of the bottom string of a two-wand loop hanging to depth b below tips 2a apart (half-ellipse
// perimeter, Ramanujan's approximation), and its inverse.
float hangingStringLength(float halfWidth, float depth);
float hangingDepth(float halfWidth, float stringLength);

// The frame of the tool for the given wand tips. stringLength is the two-wand loop's bottom string
// (fixed per film); the loop hangs in the plane of the tips and `hangTowards` (gravity for a new film, then the
// film's Film::loopHang, which swingLoop keeps continuous).
WireFrame makeWireFrame(const WandTool& tool, const WandState& wands, float stringLength, const Vec3& hangTowards);

// The unit direction from the left wand tip to the right one (the two-wand frame's `axis`); x when they meet.
Vec3 spanAxis(const WandState& wands);

// The way a two-wand loop hangs (its frame's `down`) once the tips have moved so that `axis` joins them: the way
// it hung before (`previousDown`), carried onto the new span and turned about it towards gravity by at most
// `maxTurn` radians. Hanging straight towards gravity has no continuous answer: as one tip passes over the other
// the span turns through the vertical, gravity's pull about it vanishes and then points the other way, and the
// loop would turn over in one frame (its bottom string, 0.3-0.8 m down, swung at 18 m/s in the stress run of
// docs/performance.md). A hanging string swings over instead, at a pendulum's pace: Params::loopSwingRate.
Vec3 swingLoop(const Vec3& previousDown, const Vec3& axis, const Vec3& gravity, float maxTurn);

// Frame coordinates of n points evenly spaced by arc length over u in [u0, u1) (dense sampling, then
// inversion of the cumulative length), and the arc length between two frame coordinates.
std::vector<float> evenlySpacedParameters(const WireFrame& f, float u0, float u1, int n);
float frameArcLength(const WireFrame& f, float u0, float u1);

// Frame coordinates of the particles the wire holds, about `spacing` apart along it (at least 3 per part).
// The two-wand loop gets particles at both tips (u = 0 and 1), where the wands hold it.
std::vector<float> wireParameters(const WireFrame& f, float spacing);

}  // namespace gb
