// Scene files: TOML (toml++) to RunOptions, with every mistake named by file, line and key.
#include "scene/scene_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <sstream>

#include "capture/untrusted.h"
#include "scene/builtin_scenes.h"
#include "simulation/experiments.h"

namespace gb {
namespace {

// Where a node is, for messages: "file:line:column".
std::string where(const std::string& source, const toml::source_region& region) {
  std::ostringstream out;
  out << printable(source, 300) << ':' << region.begin.line << ':' << region.begin.column;
  return out.str();
}

// A number from a scene as a message shows it: all the digits that tell it apart ("3600.0000001", not "3600"), at
// most 15 of them ("1e+300", not 301 digits).
std::string numberText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

[[noreturn]] void fail(const std::string& source, const toml::source_region& region, const std::string& message) {
  throw SceneError(where(source, region) + ": " + message);
}

constexpr double kMaxCoordinate = 1000.0;  // metres: camera and target points are checked against it

// Reads one table's keys through a handler per key; any other key is an error naming it.
class TableReader {
 public:
  TableReader(const std::string& source, std::string tableName) : source_(source), table_(std::move(tableName)) {}

  void on(const std::string& key, std::function<void(const toml::node&)> handler) {
    handlers_[key] = std::move(handler);
  }

  void read(const toml::table& table) const {
    for (auto&& [key, node] : table) {
      const auto it = handlers_.find(std::string(key.str()));
      if (it == handlers_.end())
        fail(source_, key.source(), "unknown key '" + printable(key.str()) + "'" + in() + known());
      it->second(node);
    }
  }

  [[nodiscard]] double number(const toml::node& node, const std::string& key, double lo, double hi) const {
    if (!node.is_number()) fail(source_, node.source(), key + in() + " must be a number");
    const double v = node.value<double>().value_or(0.0);
    if (!(v >= lo && v <= hi))
      fail(source_, node.source(),
           key + in() + " = " + numberText(v) + " is out of range [" + numberText(lo) + ", " + numberText(hi) + "]");
    return v;
  }
  // A whole number in any form TOML writes one: 6, 6.0, 1e7 (as the command line takes them).
  [[nodiscard]] int integer(const toml::node& node, const std::string& key, int lo, int hi) const {
    const double v = number(node, key, lo, hi);
    if (v != std::floor(v)) fail(source_, node.source(), key + in() + " = " + numberText(v) + " is not a whole number");
    return static_cast<int>(v);
  }
  [[nodiscard]] std::string text(const toml::node& node, const std::string& key,
                                 const std::vector<std::string>& choices = {}) const {
    if (!node.is_string()) fail(source_, node.source(), key + in() + " must be a string");
    std::string v = node.value<std::string>().value_or("");
    if (!choices.empty() && std::find(choices.begin(), choices.end(), v) == choices.end()) {
      std::string list;
      for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
      fail(source_, node.source(), key + in() + " = '" + printable(v) + "' is not one of: " + list);
    }
    return v;
  }
  // Text that is printed (a name, a description): one line of at most `maxBytes`, without control characters (a
  // terminal obeys an escape sequence printed raw).
  [[nodiscard]] std::string line(const toml::node& node, const std::string& key, size_t maxBytes) const {
    std::string v = text(node, key);
    if (v.size() > maxBytes)
      fail(source_, node.source(),
           key + in() + " is " + std::to_string(v.size()) + " bytes long, at most " + std::to_string(maxBytes));
    if (printable(v, v.size()) != v)
      fail(source_, node.source(),
           key + in() + " = '" + printable(v) + "' holds control characters (one line of text)");
    return v;
  }
  [[nodiscard]] bool boolean(const toml::node& node, const std::string& key) const {
    if (!node.is_boolean()) fail(source_, node.source(), key + in() + " must be true or false");
    return node.value<bool>().value_or(false);
  }
  [[nodiscard]] std::array<float, 3> point(const toml::node& node, const std::string& key) const {
    const toml::array* a = node.as_array();
    const auto isNumber = [](const toml::node& n) { return n.is_number(); };
    if (!a || a->size() != 3 || !std::all_of(a->begin(), a->end(), isNumber))
      fail(source_, node.source(), key + in() + " must be three numbers [x, y, z] (m)");
    std::array<float, 3> p{};
    for (size_t k = 0; k < 3; ++k) {
      // TOML has nan and inf; a camera there draws grey frames. kMaxCoordinate is far beyond any stage.
      const double v = (*a)[k].value<double>().value_or(0.0);
      if (!(std::abs(v) <= kMaxCoordinate))
        fail(source_, (*a)[k].source(),
             key + in() + ": " + numberText(v) + " is not a coordinate within " +
                 std::to_string(static_cast<int>(kMaxCoordinate)) + " m of the origin");
      p[k] = static_cast<float>(v);
    }
    return p;
  }

 private:
  [[nodiscard]] std::string in() const { return table_.empty() ? "" : " in [" + table_ + "]"; }
  [[nodiscard]] std::string known() const {
    std::string list;
    for (const auto& [k, h] : handlers_) list += (list.empty() ? "" : ", ") + k;
    return " (known: " + list + ")";
  }
  const std::string& source_;
  std::string table_;
  std::map<std::string, std::function<void(const toml::node&)>> handlers_;
};

// The orbit camera that sees its target from `eye` (OrbitCamera::position inverted).
void lookFrom(const Vec3& eye, OrbitCamera& camera) {
  const Vec3 back = eye - camera.target;
  camera.distance = std::max(back.norm(), 0.3f);
  camera.pitch = std::asin(std::clamp(back.y() / camera.distance, -1.0f, 1.0f));
  camera.yaw = std::atan2(back.x(), back.z());
}

const toml::table& subTable(const std::string& source, const toml::node& node, const std::string& name) {
  const toml::table* table = node.as_table();
  if (!table) fail(source, node.source(), "[" + name + "] must be a table");
  return *table;
}

// An input naming a file or folder must name one that exists; relative paths are the scene file's, inside its folder.
std::string resolveInput(const std::string& source, const toml::node& node, const std::string& spec,
                         const std::filesystem::path& baseDir) {
  for (const std::string prefix : {"trajectory:", "fakenect:"}) {
    if (spec.rfind(prefix, 0) != 0) continue;
    std::filesystem::path path = spec.substr(prefix.size());
    // A scene's relative paths stay inside its folder: a scene from elsewhere cannot have any file read by naming
    // it through "../..". An absolute path says plainly what it reads.
    if (path.is_relative() && !path.empty() && *path.lexically_normal().begin() == "..")
      fail(source, node.source(),
           "input path '" + printablePath(path) +
               "' leaves the scene's folder (a relative path is read inside it; give an absolute path for elsewhere)");
    if (path.is_relative()) path = baseDir / path;
    std::error_code ec;
    const bool wantsFolder = prefix == std::string("fakenect:");
    const std::string why = whyNotARegularFile(path);
    if (wantsFolder && !std::filesystem::is_directory(path, ec))
      fail(source, node.source(), "input folder '" + printablePath(path) + "' " + (why.empty() ? "is a file" : why));
    if (!wantsFolder && !why.empty()) fail(source, node.source(), "input file '" + printablePath(path) + "' " + why);
    return prefix + path.string();
  }
  if (spec != "kinect" && spec != "mouse" && spec.rfind("script:", 0) != 0)
    fail(source, node.source(),
         "input = '" + printable(spec) + "' is not kinect, mouse, fakenect:DIR, trajectory:FILE or script:NAME");
  if (spec.rfind("script:", 0) == 0) {
    try {
      (void)gestureFromName(spec.substr(7));
    } catch (const std::invalid_argument& e) {
      fail(source, node.source(), e.what());
    }
  }
  return spec;
}

void readParams(const std::string& source, const toml::table& table, Params& params) {
  std::map<std::string, toml::source_region> lines;
  for (auto&& [key, node] : table) {
    const std::string name(key.str());
    const ParamField* field = findParamField(name);
    if (!field)
      fail(source, key.source(), "unknown parameter '" + printable(name) + "' in [params] (docs/model.md lists them)");
    // A whole number may be written 6.0 or 1e7 (setParameter refuses one that is not whole, naming it).
    if (!node.is_number()) fail(source, node.source(), name + " in [params] must be a number");
    try {
      setParameter(params, name, node.value<double>().value_or(0.0));
    } catch (const std::invalid_argument& e) {  // an integer beyond int, say: named with its line
      fail(source, node.source(), e.what());
    }
    lines[name] = node.source();
  }
  // An out-of-range parameter is pointed at on its line when the scene set it.
  for (const ParamError& error : rangeErrors(params)) {
    const auto it = lines.find(error.name);
    if (it != lines.end()) fail(source, it->second, error.message);
    throw SceneError(source + ": " + error.message);
  }
}

// A physics experiment builds its own film and runs its own length: a scene's key it would ignore is refused by name,
// as its command-line twin is (main.cpp).
void refuseKeysForAnExperiment(const std::string& source, const toml::table& root, const std::string& experiment) {
  for (auto&& [key, node] : root) {
    const std::string_view name = key.str();
    if (name != "name" && name != "description" && name != "experiment" && name != "params")
      fail(source, key.source(),
           "'" + printable(name) + "' does not apply to the physics experiment '" + experiment +
               "', which builds its own film and runs its own length (a scene of one takes name, description, "
               "experiment and [params]; docs/validation.md)");
  }
}

}  // namespace

Scene parseScene(std::string_view text, const std::string& source, const std::filesystem::path& baseDir) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    fail(source, e.source(), printable(e.description(), 300));  // toml++ may quote the byte it stopped at
  }
  Scene scene;
  RunOptions& run = scene.run;
  TableReader top(source, "");
  top.on("name", [&](const toml::node& n) { scene.name = top.line(n, "name", 64); });
  top.on("description", [&](const toml::node& n) { scene.description = top.line(n, "description", 300); });
  top.on("duration", [&](const toml::node& n) { run.duration = top.number(n, "duration", 0.001, kMaxRunSeconds); });
  bool burstAtSet = false;
  top.on("burst_at", [&](const toml::node& n) {
    run.burstAt = top.number(n, "burst_at", kNeverBurst, kMaxRunSeconds);  // as --burst-at: negative is never
    burstAtSet = true;
  });
  top.on("experiment", [&](const toml::node& n) { run.experiment = top.text(n, "experiment", experimentNames()); });

  TableReader tool(source, "tool");
  tool.on("kind", [&](const toml::node& n) {
    run.tool.kind = tool.text(n, "kind", {"two-wands", "ring"}) == "ring" ? ToolKind::Ring : ToolKind::TwoWands;
  });
  tool.on("loop_depth", [&](const toml::node& n) {
    run.tool.loopDepth = static_cast<float>(tool.number(n, "loop_depth", 0.05, 5.0));
  });
  tool.on("ring_radius", [&](const toml::node& n) {
    run.tool.ringRadius = static_cast<float>(tool.number(n, "ring_radius", 0.02, 5.0));
  });
  top.on("tool", [&](const toml::node& n) { tool.read(subTable(source, n, "tool")); });

  TableReader input(source, "input");
  input.on("source",
           [&](const toml::node& n) { run.input.input = resolveInput(source, n, input.text(n, "source"), baseDir); });
  input.on("stabilizer", [&](const toml::node& n) {
    run.input.stabilizer = input.text(n, "stabilizer", {"bspline", "one-euro"});
  });
  input.on("speed", [&](const toml::node& n) {
    run.gestureOptions.speed = static_cast<float>(input.number(n, "speed", 0.0, 20.0));
  });
  input.on("start", [&](const toml::node& n) {
    run.gestureOptions.start = static_cast<float>(input.number(n, "start", 0.0, 3600.0));
  });
  input.on("stroke", [&](const toml::node& n) {
    run.gestureOptions.duration = static_cast<float>(input.number(n, "stroke", 0.01, 3600.0));
  });
  input.on("tip_separation", [&](const toml::node& n) {
    run.gestureOptions.tipSeparation = static_cast<float>(input.number(n, "tip_separation", 0.05, 5.0));
  });
  input.on("height", [&](const toml::node& n) {
    run.gestureOptions.height = static_cast<float>(input.number(n, "height", 0.1, 5.0));
  });
  top.on("input", [&](const toml::node& n) { input.read(subTable(source, n, "input")); });

  top.on("params", [&](const toml::node& n) { readParams(source, subTable(source, n, "params"), run.params); });

  TableReader output(source, "output");
  output.on("ply_every", [&](const toml::node& n) { run.plyEvery = output.integer(n, "ply_every", 0, 1000000); });
  output.on("images_every",
            [&](const toml::node& n) { run.imageEvery = output.integer(n, "images_every", 0, 1000000); });
  top.on("output", [&](const toml::node& n) { output.read(subTable(source, n, "output")); });

  TableReader view(source, "render");
  RenderOutputOptions& render = run.render;
  std::optional<std::array<float, 3>> eye;
  view.on("enabled", [&](const toml::node& n) { render.enabled = view.boolean(n, "enabled"); });
  view.on("width", [&](const toml::node& n) { render.image.width = view.integer(n, "width", 16, 16384); });
  view.on("height", [&](const toml::node& n) { render.image.height = view.integer(n, "height", 16, 16384); });
  view.on("colouring", [&](const toml::node& n) {
    render.image.colouring = colouringFromName(view.text(n, "colouring", {"interference", "thickness", "airflow"}));
  });
  view.on("every", [&](const toml::node& n) { render.pngEvery = view.integer(n, "every", 0, 1000000); });
  view.on("scale", [&](const toml::node& n) {
    render.drawnScale = static_cast<float>(view.number(n, "scale", kSmallestDrawnScale, 1.0));
  });
  view.on("video", [&](const toml::node& n) { render.video = view.boolean(n, "video") ? "render.mp4" : ""; });
  view.on("video_fps", [&](const toml::node& n) { render.videoFps = view.number(n, "video_fps", 1.0, 1000.0); });
  view.on("camera", [&](const toml::node& n) { eye = view.point(n, "camera"); });
  view.on("target", [&](const toml::node& n) {
    const auto t = view.point(n, "target");
    render.camera.target = Vec3(t[0], t[1], t[2]);
  });
  top.on("render", [&](const toml::node& n) { view.read(subTable(source, n, "render")); });

  top.read(root);
  if (!run.experiment.empty()) refuseKeysForAnExperiment(source, root, run.experiment);
  // A scene written for a recorded or live input pokes it when it says so; a scene's poke for its script does
  // not follow the performance to another input (--input on the command line).
  run.burstOnAnyInput = burstAtSet && !run.input.scripted();
  if (eye) lookFrom(Vec3((*eye)[0], (*eye)[1], (*eye)[2]), render.camera);
  if (scene.name.empty()) throw SceneError(source + ": the scene has no name (name = \"...\")");
  return scene;
}

Scene loadSceneFile(const std::filesystem::path& path) {
  // Opened as a regular file only: a folder opens as an empty file, and a FIFO or a device would block or never end.
  const std::string named = "scene file '" + printablePath(path) + "'";
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneError(named + " is a folder; give a .toml file in it");
  std::string why, text;
  const InputFile file = openInputFile(path, kMaxSceneBytes, why);
  if (!file) throw SceneError(named + " " + why + " (a scene is read from a regular file)");
  if (!readWhole(file.get(), text, why)) throw SceneError(named + " " + why);
  return parseScene(text, path.string(), path.parent_path());
}

std::vector<std::string> builtinSceneNames() {
  std::vector<std::string> names;
  for (const BuiltinScene& s : builtinScenes()) names.emplace_back(s.name);
  return names;
}

Scene builtinScene(const std::string& name) {
  for (const BuiltinScene& s : builtinScenes())
    if (name == s.name) return parseScene(s.text, "builtin:" + name, std::filesystem::current_path());
  std::string list;
  for (const std::string& n : builtinSceneNames()) list += (list.empty() ? "" : ", ") + n;
  throw SceneError("unknown scene '" + printable(name) + "' (built-in scenes: " + list +
                   "; or give a path to a .toml file)");
}

Scene resolveScene(const std::string& nameOrPath) {
  const std::vector<std::string> names = builtinSceneNames();
  const bool builtin = std::find(names.begin(), names.end(), nameOrPath) != names.end();
  std::error_code ec;
  const bool looksLikePath = nameOrPath.find('/') != std::string::npos || nameOrPath.ends_with(".toml") ||
                             (!builtin && std::filesystem::exists(nameOrPath, ec));
  return looksLikePath ? loadSceneFile(nameOrPath) : builtinScene(nameOrPath);
}

}  // namespace gb
