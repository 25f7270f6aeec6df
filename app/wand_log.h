#pragma once
// The wands of a run, frame by frame: wands.csv (written as the run goes) and, at the end, wands.svg, the
// input hands against the wands (trajectory_plot.h). docs/formats.md describes both.

#include <cstdio>
#include <filesystem>
#include <string>

#include "trajectory_plot.h"
#include "wand_input.h"

namespace gb {

class WandLog {
 public:
  explicit WandLog(const std::filesystem::path& csv);
  ~WandLog();
  WandLog(const WandLog&) = delete;  // owns the open file
  WandLog& operator=(const WandLog&) = delete;
  void add(double time, const WandFrame& frame);
  void writePlot(const std::filesystem::path& svg, const std::string& title) const;

 private:
  std::FILE* file_ = nullptr;
  TrajectoryPlot plot_;
};

}  // namespace gb
