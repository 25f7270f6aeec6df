#pragma once
// Scenes as data (docs/formats.md "Scene files"): a TOML file holds the tool, the input, every model parameter, the
// output and render settings and the duration of a run. The paper's figures are built-in scenes (scenes/*.toml,
// embedded at build time), listed by `giantbubble scenes` and run by `giantbubble run --scene NAME`.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "scene/run_options.h"

namespace gb {

// A scene that cannot be used; the message names the file (or builtin:NAME), the line and column, and the key.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Scene {
  std::string name;
  std::string description;  // one line, for `giantbubble scenes`
  RunOptions run;           // everything a run needs (render settings in run.render), from the defaults
};

// Parses a scene. `source` names it in messages; relative input paths resolve against `baseDir`. Unknown
// keys, wrong types, out-of-range values and missing input files are SceneErrors.
Scene parseScene(std::string_view text, const std::string& source, const std::filesystem::path& baseDir);

// The largest scene file read (bytes): the built-in scenes are under 2 KiB.
inline constexpr std::uintmax_t kMaxSceneBytes = 1 << 20;

// A scene file on disk (SceneError if it cannot be read, is not a regular file or is over kMaxSceneBytes).
Scene loadSceneFile(const std::filesystem::path& path);

// The built-in scenes, in the order of the paper's figures.
std::vector<std::string> builtinSceneNames();
Scene builtinScene(const std::string& name);  // SceneError naming the choices for an unknown name

// A built-in scene's name or a path to a scene file.
Scene resolveScene(const std::string& nameOrPath);

}  // namespace gb
