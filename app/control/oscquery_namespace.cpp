#include "app/control/oscquery_namespace.h"

#include <utility>

#include "app/control/param_catalog.h"
#include "app/show/osc_cues.h"

namespace gb {
namespace {

using json = nlohmann::ordered_json;

constexpr CueAction kCues[] = {CueAction::Dip,       CueAction::Burst,  CueAction::Reset,      CueAction::Pause,
                               CueAction::Colouring, CueAction::Camera, CueAction::Fullscreen, CueAction::PerformerView,
                               CueAction::Operator,  CueAction::Quit};

constexpr std::pair<const char*, const char*> kCueMeanings[] = {{"dip", "dip the wands: a new film"},
                                                                {"burst", "burst the film"},
                                                                {"reset", "the input and the film from the start"},
                                                                {"pause", "1 pauses, 0 resumes"},
                                                                {"colouring", "the next colouring"},
                                                                {"camera", "the camera back to following the film"},
                                                                {"fullscreen", "full screen or a window"},
                                                                {"performer_view", "the performer view on or off"},
                                                                {"operator", "the operator overlay on or off"},
                                                                {"quit", "end the show"}};

json container(const std::string& path) { return {{"FULL_PATH", path}, {"CONTENTS", json::object()}}; }

json paramNode(const ParamInfo& info, const Params& params) {
  const ParamField& f = *info.field;
  json node = {{"FULL_PATH", std::string("/giantbubble/param/") + f.name},
               {"TYPE", info.integer() ? "i" : "f"},
               {"ACCESS", info.timing == ParamTiming::Start ? 1 : 3},
               {"RANGE", json::array({{{"MIN", f.lo}, {"MAX", f.hi}}})},
               {"CLIPMODE", "none"},
               {"UNIT", json::array({info.unit()})},
               {"DESCRIPTION", info.description},
               {"TAGS", json::array({info.group})}};
  if (info.integer())
    node["VALUE"] = json::array({params.*f.integer});
  else
    node["VALUE"] = json::array({params.*f.real});
  if (info.timing == ParamTiming::NextFilm) node["TAGS"].push_back("next_film");
  if (info.timing == ParamTiming::Start) node["TAGS"].push_back("start_only");
  return node;
}

std::string meaningOf(const std::string& cue) {
  for (const auto& [name, meaning] : kCueMeanings)
    if (cue == name) return meaning;
  return {};
}

json cueNode(CueAction action) {
  const std::string name = cueName(action);
  return {{"FULL_PATH", "/giantbubble/" + name},
          {"TYPE", "i"},
          {"ACCESS", 2},
          {"RANGE", json::array({{{"MIN", 0}, {"MAX", 1}}})},
          {"DESCRIPTION", meaningOf(name)}};
}

json statusNode(const std::string& name, const json& value, const char* type, const char* unit,
                const char* description) {
  return {{"FULL_PATH", "/giantbubble/status/" + name},
          {"TYPE", type},
          {"ACCESS", 1},
          {"VALUE", json::array({value})},
          {"UNIT", json::array({unit})},
          {"DESCRIPTION", description}};
}

json statusNodes(const ShowStatus& s) {
  json nodes = container("/giantbubble/status");
  auto& c = nodes["CONTENTS"];
  c["fps"] = statusNode("fps", s.framesPerSecond, "f", "", "frames presented per second, over the last second");
  c["realtime_factor"] = statusNode("realtime_factor", s.realTimeFactor, "f", "",
                                    "simulated seconds per wall-clock second, over the last second");
  c["film_area"] = statusNode("film_area", s.filmArea, "f", "m^2", "the film's area");
  c["film_state"] = statusNode("film_state", s.filmState, "s", "", "on_wands, free_bubble or none");
  c["performer"] = statusNode("performer", s.performer, "s", "", "found, waiting or none (no camera)");
  c["last_event"] = statusNode("last_event", s.lastEvent, "s", "", "the show's last console line");
  c["paused"] = statusNode("paused", s.paused ? 1 : 0, "i", "", "1 while paused");
  return nodes;
}

json presetNodes(const std::vector<std::string>& names) {
  json recall = {{"FULL_PATH", "/giantbubble/preset"},
                 {"TYPE", "s"},
                 {"ACCESS", 2},
                 {"RANGE", json::array({{{"VALS", names}}})},
                 {"DESCRIPTION", "recall a preset: its parameters now, those of a new film at the next dip"},
                 {"CONTENTS", json::object()}};
  recall["CONTENTS"]["save"] = {{"FULL_PATH", "/giantbubble/preset/save"},
                                {"TYPE", "s"},
                                {"ACCESS", 2},
                                {"DESCRIPTION", "save the parameters as a preset of this name"}};
  return recall;
}

}  // namespace

json oscQueryNamespace(const ControlState& state) {
  const Params params = state.params.get();
  json params_node = container("/giantbubble/param");
  for (const ParamInfo& info : paramCatalog()) params_node["CONTENTS"][info.field->name] = paramNode(info, params);
  json show = container("/giantbubble");
  show["DESCRIPTION"] = "giantbubble live: a giant soap bubble simulation";
  show["CONTENTS"]["param"] = std::move(params_node);
  for (CueAction action : kCues) show["CONTENTS"][cueName(action)] = cueNode(action);
  show["CONTENTS"]["preset"] = presetNodes(state.presets.get());
  show["CONTENTS"]["status"] = statusNodes(state.status.get());
  json root = container("/");
  root["CONTENTS"]["giantbubble"] = std::move(show);
  return root;
}

const json* oscQueryNode(const json& root, const std::string& path) {
  if (path.empty() || path.front() != '/') return nullptr;
  const json* node = &root;
  size_t from = 1;
  while (from < path.size()) {
    size_t to = path.find('/', from);
    if (to == std::string::npos) to = path.size();
    const std::string part = path.substr(from, to - from);
    if (!part.empty()) {
      const auto contents = node->find("CONTENTS");
      if (contents == node->end() || !contents->contains(part)) return nullptr;
      node = &(*contents)[part];
    }
    from = to + 1;
  }
  return node;
}

json oscQueryHostInfo(int oscPort) {
  json extensions = json::object();
  for (const char* e : {"ACCESS", "VALUE", "RANGE", "DESCRIPTION", "TAGS", "UNIT", "CLIPMODE", "LISTEN", "FULL_PATH",
                        "CONTENTS", "TYPE"})
    extensions[e] = true;
  for (const char* e :
       {"PATH_CHANGED", "PATH_RENAMED", "PATH_ADDED", "PATH_REMOVED", "CRITICAL", "OVERLOADS", "EXTENDED_TYPE", "HTML"})
    extensions[e] = false;
  return {{"NAME", "giantbubble"}, {"OSC_PORT", oscPort}, {"OSC_TRANSPORT", "UDP"}, {"EXTENSIONS", extensions}};
}

const json* oscQueryValue(const json& root, const std::string& path) {
  const json* node = oscQueryNode(root, path);
  if (!node) return nullptr;
  const auto value = node->find("VALUE");
  return value == node->end() ? nullptr : &*value;
}

}  // namespace gb
