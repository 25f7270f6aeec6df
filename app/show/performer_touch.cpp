#include "app/show/performer_touch.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace gb {

void givePerformerBody(Simulation& sim, const WandFrame& frame) {
  if (!frame.body || frame.body->empty()) {
    sim.clearBody();
    return;
  }
  if (sim.bodyTime() == frame.bodyTime) return;  // this depth frame's body is already the film's collider
  BodyPoints body{*frame.body, {}, frame.bodyTime};
  // The hands as measured, and the wand tips the stabilizer carries them to (behind the hands by its lag): the film's
  // corners are at the tips, the hand's own points at the measured hands.
  for (const Vec3& grip : {frame.leftHand, frame.rightHand, frame.wands.leftPosition, frame.wands.rightPosition})
    if (grip.allFinite()) body.grips.push_back(grip);
  sim.setBody(body);
}

namespace {

// The icosphere's subdivisions whose edges are at most kBubbleEdge: an icosahedron's edge is 1.05 times its radius,
// halved by each subdivision. 1.5 cm keeps the particles closer than the touch distance (2 cm), so that a fingertip
// finds one.
constexpr float kBubbleEdge = 0.015f;
constexpr int kMostSubdivisions = 6;  // 40,962 particles: a 0.3 m bubble of world radius stays within a show's film

int subdivisionsFor(float radius) {
  int subdivisions = 0;
  while (subdivisions < kMostSubdivisions && 1.05f * radius / std::ldexp(1.0f, subdivisions) > kBubbleEdge)
    ++subdivisions;
  return subdivisions;
}

}  // namespace

std::unique_ptr<Simulation> startingSimulation(const RunOptions& o, const WandInput& input, const WandState& wands,
                                               std::unique_ptr<Stepper> stepper) {
  if (!o.input.bubbleAt) return std::make_unique<Simulation>(o.params, o.tool, wands, std::move(stepper));
  const Calibration* calibration = input.cameraCalibration();
  if (!calibration)
    throw std::invalid_argument(
        "--bubble-at places the bubble in camera space: it needs an input that has one (--input kinect, "
        "fakenect:DIR or trajectory:FILE), not a script");
  const auto& [x, y, z] = *o.input.bubbleAt;
  const Vec3 centre = calibration->toWorld(Vec3d(x, y, z)).cast<float>();
  const auto radius = static_cast<float>(o.input.bubbleRadius * calibration->reach);
  Params params = o.params;
  params.bubbleLift = 1.0f;  // neutrally buoyant: it floats still until something touches it
  auto sim = std::make_unique<Simulation>(params, generateSphere(params, centre, radius, subdivisionsFor(radius)),
                                          wands, std::move(stepper));
  sim->setWandsArmed({false, false});
  return sim;
}

std::string bubbleInWords(const RunOptions& o, const Simulation& sim) {
  if (!o.input.bubbleAt) return "";
  const auto& [x, y, z] = *o.input.bubbleAt;
  char words[200];
  std::snprintf(words, sizeof words,
                "a still free bubble of radius %.3f m at (%.3f, %.3f, %.3f) m of camera space, %zu particles",
                o.input.bubbleRadius, x, y, z, sim.particleCount());
  return words;
}

std::string touchInWords(const Simulation& sim, const std::string& events) {
  if (events.find("burst_by_touch") == std::string::npos || !sim.lastTouch()) return "";
  const Touch& t = *sim.lastTouch();
  char words[160];
  std::snprintf(words, sizeof words, "burst by the performer's touch at (%.3f, %.3f, %.3f) m, closing at %.2f m/s",
                t.position.x(), t.position.y(), t.position.z(), t.approachSpeed);
  return words;
}

}  // namespace gb
