#pragma once
// Presets of a show (live --presets DIR): every parameter under a name, saved as a scene file (DIR/NAME.toml, the
// format --scene reads: a name, a description and [params]) and recalled live by OSC (/giantbubble/preset NAME),
// from the control page or with a key. A recall sets each parameter the file lists that differs through LiveParams,
// so it is checked as a set is, and what only a new film can take waits for the next dip.

#include <filesystem>
#include <string>
#include <vector>

#include "model/params.h"

namespace gb {

class PresetLibrary {
 public:
  // Presets in `dir` (made when the first preset is saved).
  explicit PresetLibrary(std::filesystem::path dir) : dir_(std::move(dir)) {}

  // The presets saved, by name, sorted.
  [[nodiscard]] std::vector<std::string> names() const;
  // Saves `params` as NAME. Throws std::invalid_argument for a name that is not 1-64 letters, digits, '-' or '_',
  // std::runtime_error naming the file when it cannot be written.
  void save(const std::string& name, const Params& params) const;
  // The parameters of preset NAME, and the names its [params] lists (a file written by hand may list a few: a
  // recall sets only those). Throws std::invalid_argument for a bad name, SceneError for a file that is missing or
  // cannot be read.
  [[nodiscard]] Params load(const std::string& name, std::vector<std::string>* listed = nullptr) const;

  [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
  [[nodiscard]] std::filesystem::path fileOf(const std::string& name) const;
};

// The TOML of a preset: name, description and every parameter in [params], floats to their last digit.
std::string presetToml(const std::string& name, const Params& params);

}  // namespace gb
