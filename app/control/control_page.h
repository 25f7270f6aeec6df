#pragma once
// The control page served at /control (control_server.h): cue buttons, the parameters as sliders grouped as the
// docs group them, presets and the show's status, for a phone or a tablet. One HTML document with its script and
// style inside: it loads nothing else. It reads the OSCQuery namespace, listens to the values over the WebSocket and
// sends cues and sets there as OSC.

#include <string_view>

namespace gb {

std::string_view controlPageHtml();

}  // namespace gb
