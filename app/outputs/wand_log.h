#pragma once
// The wands of a run, frame by frame: wands.csv (written as the run goes) and, at the end, wands.svg, the
// input hands against the wands (trajectory_plot.h). docs/formats.md describes both.

#include <filesystem>
#include <optional>
#include <string>

#include "capture/output_file.h"
#include "capture/trajectory_plot.h"
#include "capture/wand_input.h"

namespace gb {

class WandLog {
 public:
  explicit WandLog(const std::filesystem::path& csv);
  void add(double time, const WandFrame& frame);  // a row of wands.csv; OutputError when it cannot be written
  void close();
  // camera: where the camera stands in the world, drawn in the scene panels when given.
  void writePlot(const std::filesystem::path& svg, const std::string& title, const std::optional<Vec3>& camera) const;

 private:
  RowFile csv_;
  TrajectoryPlot plot_;
};

}  // namespace gb
