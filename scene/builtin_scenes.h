#pragma once
// The built-in scenes: scenes/*.toml, embedded as text at build time (scene/CMakeLists.txt).

#include <span>

namespace gb {

struct BuiltinScene {
  const char* name;  // the file name without .toml
  const char* text;  // the TOML
};

std::span<const BuiltinScene> builtinScenes();  // sorted by name: the experiments, then the paper's figures in order

}  // namespace gb
