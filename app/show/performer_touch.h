#pragma once
// The performer's body, as the input's newest depth frame shows it, given to the film as its collider
// (cpu-reference/topology/body_touch.h): every command that steps a film under camera input calls this each frame.

#include "simulation.h"
#include "wand_input.h"

namespace gb {

// A new depth frame's body points go to the simulation, with the measured hands as the grips (the hands on the wands
// do not burst their own film); an input that shows no body takes the collider away.
void givePerformerBody(Simulation& sim, const WandFrame& frame);

}  // namespace gb
