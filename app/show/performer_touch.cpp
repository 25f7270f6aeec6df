#include "performer_touch.h"

namespace gb {

void givePerformerBody(Simulation& sim, const WandFrame& frame) {
  if (!frame.body || frame.body->empty()) {
    sim.clearBody();
    return;
  }
  if (sim.bodyTime() == frame.bodyTime) return;  // this depth frame's body is already the film's collider
  BodyPoints body{*frame.body, {}, frame.bodyTime};
  for (const Vec3& hand : {frame.leftHand, frame.rightHand})
    if (hand.allFinite()) body.grips.push_back(hand);
  sim.setBody(body);
}

}  // namespace gb
