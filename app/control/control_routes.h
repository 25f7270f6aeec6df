#pragma once
// What the control server answers (control_server.h), read from the show's ControlState: the OSCQuery namespace
// and HOST_INFO, the control page, and the values LISTENing clients follow.

#include "app/control/control_server.h"
#include "app/control/control_state.h"

namespace gb {

// `state` outlives the routes; oscPort is the show's OSC port for HOST_INFO.
ControlRoutes makeControlRoutes(const ControlState& state, int oscPort);

}  // namespace gb
