#include "performer_touch.h"

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

}  // namespace gb
