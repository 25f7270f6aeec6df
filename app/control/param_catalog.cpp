#include "app/control/param_catalog.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <vector>

#include "app/control/param_docs.h"

namespace gb {
namespace {

// Parameters that shape a film as it is made: changed during a film they would disagree with the film on stage.
constexpr const char* kNextFilm[] = {"particlesAtFullSolution", "solution",        "solutionReserve", "areaWeight",
                                     "springPrestrain",         "coarsePatchRings"};

std::string trim(std::string s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

// Each field's group: the "// --- Group (references) ---" comment above it in shared_params.h.
std::map<std::string, std::string> groupsOf(std::string_view source) {
  std::map<std::string, std::string> groups;
  std::istringstream lines{std::string(source)};
  std::string line, group = "Other";
  while (std::getline(lines, line)) {
    const std::string t = trim(line);
    if (t.starts_with("// --- ")) {
      group = t.substr(7);
      group = trim(group.substr(0, std::min(group.find(" ("), group.find(" ---"))));
      continue;
    }
    for (const char* type : {"float ", "int "}) {
      if (!t.starts_with(type)) continue;
      const std::string rest = t.substr(std::string(type).size());
      groups.emplace(rest.substr(0, rest.find_first_of(" ;")), group);
    }
  }
  return groups;
}

// Each name's meaning: the last cell of its row in docs/model.md's parameter table (`gravityX/Y/Z` for three).
std::map<std::string, std::string> meaningsOf(std::string_view document) {
  std::map<std::string, std::string> meanings;
  std::istringstream lines{std::string(document)};
  std::string line;
  while (std::getline(lines, line)) {
    if (!line.starts_with("| `")) continue;
    const auto close = line.find('`', 3);
    const auto cell = line.rfind(" | ");
    if (close == std::string::npos || cell == std::string::npos || cell < close) continue;
    std::string meaning = trim(line.substr(cell + 3));
    if (meaning.ends_with("|")) meaning = trim(meaning.substr(0, meaning.size() - 1));
    std::erase(meaning, '`');  // the table's code marks are Markdown; an OSCQuery client shows DESCRIPTION as text
    const std::string name = line.substr(3, close - 3);
    if (name == "gravityX/Y/Z")
      for (const char* axis : {"gravityX", "gravityY", "gravityZ"}) meanings.emplace(axis, meaning);
    else
      meanings.emplace(name, meaning);
  }
  return meanings;
}

std::vector<ParamInfo> buildCatalog() {
  const auto groups = groupsOf(sharedParamsSource());
  const auto meanings = meaningsOf(modelDocument());
  std::vector<ParamInfo> catalog;
  for (const ParamField& f : paramFields()) {
    ParamInfo info;
    info.field = &f;
    const auto group = groups.find(f.name);
    info.group = group == groups.end() ? "Other" : group->second;
    const auto meaning = meanings.find(f.name);
    info.description = meaning == meanings.end() ? "" : meaning->second;
    if (std::string(f.name) == "frameTime") info.timing = ParamTiming::Start;
    for (const char* name : kNextFilm)
      if (std::string(f.name) == name) info.timing = ParamTiming::NextFilm;
    catalog.push_back(std::move(info));
  }
  return catalog;
}

}  // namespace

std::string ParamInfo::unit() const { return trim(field->unit); }

std::span<const ParamInfo> paramCatalog() {
  static const std::vector<ParamInfo> catalog = buildCatalog();
  return catalog;
}

const ParamInfo* findParamInfo(const std::string& name) {
  for (const ParamInfo& info : paramCatalog())
    if (name == info.field->name) return &info;
  return nullptr;
}

double paramValue(const Params& params, const ParamField& field) {
  return field.real ? static_cast<double>(params.*field.real) : static_cast<double>(params.*field.integer);
}

}  // namespace gb
