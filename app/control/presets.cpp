#include "app/control/presets.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "scene/scene_file.h"

namespace gb {
namespace {

bool validName(const std::string& name) {
  return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
  });
}

}  // namespace

std::string presetToml(const std::string& name, const Params& params) {
  std::string text = "name = \"" + name + "\"\ndescription = \"preset " + name + " of giantbubble live\"\n\n[params]\n";
  for (const ParamField& f : paramFields()) {
    char value[64];
    if (f.real)  // 9 significant digits: a float read back is the same float
      std::snprintf(value, sizeof value, "%.9g", static_cast<double>(params.*f.real));
    else
      std::snprintf(value, sizeof value, "%d", params.*f.integer);
    std::string v = value;
    if (f.real && v.find_first_of(".eEn") == std::string::npos) v += ".0";  // TOML: a float, not an integer
    text += std::string(f.name) + " = " + v + "\n";
  }
  return text;
}

std::filesystem::path PresetLibrary::fileOf(const std::string& name) const {
  if (!validName(name))
    throw std::invalid_argument("preset name '" + name.substr(0, 80) +
                                "': 1 to 64 letters, digits, '-' or '_' are allowed");
  return dir_ / (name + ".toml");
}

std::vector<std::string> PresetLibrary::names() const {
  std::vector<std::string> found;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dir_, error)) {
    const std::string stem = entry.path().stem().string();
    if (entry.path().extension() == ".toml" && validName(stem)) found.push_back(stem);
  }
  std::sort(found.begin(), found.end());
  return found;
}

void PresetLibrary::save(const std::string& name, const Params& params) const {
  const std::filesystem::path file = fileOf(name);
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  std::ofstream out(file);
  out << presetToml(name, params);
  out.close();
  if (!out) throw std::runtime_error("cannot write preset file " + file.string());
}

Params PresetLibrary::load(const std::string& name, std::vector<std::string>* listed) const {
  const std::filesystem::path file = fileOf(name);
  const Params params = loadSceneFile(file).run.params;  // checked as --scene checks it
  if (listed) {
    listed->clear();
    const toml::table root = toml::parse_file(file.string());
    if (const toml::table* table = root["params"].as_table())
      for (const auto& [key, value] : *table) listed->emplace_back(key.str());
  }
  return params;
}

}  // namespace gb
