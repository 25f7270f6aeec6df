#include "app/control/control_routes.h"

#include "app/control/control_page.h"
#include "app/control/oscquery_namespace.h"

namespace gb {
namespace {

using json = nlohmann::ordered_json;

HttpAnswer jsonAnswer(const json& body) { return {200, "application/json", body.dump()}; }
HttpAnswer notFound(const std::string& what) { return {404, "text/plain", what + "\n"}; }

HttpAnswer get(const ControlState& state, int oscPort, const std::string& path, const std::string& attribute) {
  if (path == "/control" || path == "/control/")
    return {200, "text/html; charset=utf-8", std::string(controlPageHtml())};
  if (attribute == "HOST_INFO") return jsonAnswer(oscQueryHostInfo(oscPort));
  const json root = oscQueryNamespace(state);
  const json* node = oscQueryNode(root, path);
  if (!node) return notFound("no such node: " + path.substr(0, 200));
  if (attribute.empty()) return jsonAnswer(*node);
  const auto value = node->find(attribute);
  if (value == node->end()) return {204, "application/json", ""};  // OSCQuery: a node without that attribute
  return jsonAnswer(json{{attribute, *value}});
}

// Every node's VALUE under `node`, by address.
void collectValues(const json& node, std::map<std::string, OscValue>& values) {
  if (const auto contents = node.find("CONTENTS"); contents != node.end())
    for (const auto& child : contents->items()) collectValues(child.value(), values);
  const auto value = node.find("VALUE");
  if (value == node.end() || value->empty()) return;
  const json& v = (*value)[0];
  OscValue osc;
  if (v.is_string()) {
    osc.type = 's';
    osc.text = v.get<std::string>();
  } else if (v.is_number_integer()) {
    osc.type = 'i';
    osc.number = v.get<double>();
  } else if (v.is_number()) {
    osc.number = v.get<double>();
  } else {
    return;
  }
  values[node["FULL_PATH"].get<std::string>()] = osc;
}

}  // namespace

ControlRoutes makeControlRoutes(const ControlState& state, int oscPort) {
  ControlRoutes routes;
  routes.get = [&state, oscPort](const std::string& path, const std::string& attribute) {
    return get(state, oscPort, path, attribute);
  };
  routes.values = [&state] {
    std::map<std::string, OscValue> values;
    collectValues(oscQueryNamespace(state), values);
    return values;
  };
  return routes;
}

}  // namespace gb
