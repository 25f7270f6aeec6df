#pragma once
// The show's OSCQuery namespace (github.com/Vidvox/OSCQueryProposal): a JSON tree of nodes, each with FULL_PATH and
// either CONTENTS (a container) or the attributes of an OSC method: TYPE (OSC type tags), ACCESS (1 read, 2 write,
// 3 both), VALUE, RANGE, UNIT, DESCRIPTION, TAGS (here the parameter's group as the docs give it, and "next_film"
// for a parameter that takes effect at the next dip). Nodes:
//
//   /giantbubble/param/NAME     f or i, ACCESS 3   every model parameter (param_catalog.h)
//   /giantbubble/CUE            i, ACCESS 2        the cues of osc_cues.h: 1 triggers (pause: 1 pauses, 0 resumes)
//   /giantbubble/preset         s, ACCESS 2        recall a preset by name; RANGE VALS lists the saved ones
//   /giantbubble/preset/save    s, ACCESS 2        save the parameters as a preset of that name
//   /giantbubble/status/NAME    ACCESS 1           fps, realtime_factor, film_area, film_state, performer,
//                                                  last_event, paused

#include <nlohmann/json.hpp>
#include <string>

#include "app/control/control_state.h"

namespace gb {

// The whole namespace with current values.
nlohmann::ordered_json oscQueryNamespace(const ControlState& state);

// The node at an OSC address ("/" the root) of a namespace, or nothing when there is none.
const nlohmann::ordered_json* oscQueryNode(const nlohmann::ordered_json& root, const std::string& path);

// HOST_INFO: the server's name, its OSC port (UDP) and the extensions it supports.
nlohmann::ordered_json oscQueryHostInfo(int oscPort);

// The VALUE array of a method's node (one element); nullptr for a container, a write-only method or no node.
const nlohmann::ordered_json* oscQueryValue(const nlohmann::ordered_json& root, const std::string& path);

}  // namespace gb
