#pragma once
// The performer's body, as the input's newest depth frame shows it, given to the film as its collider
// (cpu-reference/topology/body_touch.h): every command that steps a film under camera input calls this each frame.

#include <memory>
#include <string>

#include "capture/wand_input.h"
#include "scene/run_options.h"
#include "simulation/simulation.h"

namespace gb {

// A new depth frame's body points go to the simulation, with the measured hands as the grips (the hands on the wands
// do not burst their own film); an input that shows no body takes the collider away.
void givePerformerBody(Simulation& sim, const WandFrame& frame);

// The simulation a run or the show starts with: a film dipped on the tool at `wands`, or, with --bubble-at, a still
// free bubble where the input's camera space puts it. That bubble's centre and radius map into the world as the hands
// do (its radius times the reach); its air carries its weight (bubbleLift 1), so it floats there from t = 0; and the
// wand tips, which may start inside it, burst it only once they have been clear of it. Throws std::invalid_argument
// when the input has no camera space (a script).
std::unique_ptr<Simulation> startingSimulation(const RunOptions& options, const WandInput& input,
                                               const WandState& wands, std::unique_ptr<Stepper> stepper);

// The --bubble-at bubble in words for the console ("" without one).
std::string bubbleInWords(const RunOptions& options, const Simulation& sim);

// The frame's touch that burst the film, in words for the console ("" when the body burst nothing this frame):
// where (world metres) and how fast it struck.
std::string touchInWords(const Simulation& sim, const std::string& events);

}  // namespace gb
