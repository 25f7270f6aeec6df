#include "wand_log.h"

#include <cmath>
#include <stdexcept>

namespace gb {

WandLog::WandLog(const std::filesystem::path& csv) {
  file_ = std::fopen(csv.c_str(), "w");
  if (!file_) throw std::runtime_error("cannot write " + csv.string());
  std::fputs(
      "time_s,left_wand_x,left_wand_y,left_wand_z,right_wand_x,right_wand_y,right_wand_z,"
      "left_wand_vx,left_wand_vy,left_wand_vz,right_wand_vx,right_wand_vy,right_wand_vz,"
      "left_hand_x,left_hand_y,left_hand_z,right_hand_x,right_hand_y,right_hand_z\n",
      file_);
}

WandLog::~WandLog() {
  if (file_) std::fclose(file_);
}

void WandLog::add(double time, const WandFrame& f) {
  std::fprintf(file_, "%.4f", time);
  for (const Vec3& v : {f.wands.leftPosition, f.wands.rightPosition, f.wands.leftVelocity, f.wands.rightVelocity})
    std::fprintf(file_, ",%.5f,%.5f,%.5f", v.x(), v.y(), v.z());
  for (const Vec3& v : {f.leftHand, f.rightHand}) {
    if (v.allFinite())
      std::fprintf(file_, ",%.5f,%.5f,%.5f", v.x(), v.y(), v.z());
    else
      std::fputs(",,,", file_);
  }
  std::fputc('\n', file_);
  std::fflush(file_);
  plot_.leftWand.push_back(f.wands.leftPosition);
  plot_.rightWand.push_back(f.wands.rightPosition);
  plot_.leftInput.push_back(f.leftHand);
  plot_.rightInput.push_back(f.rightHand);
}

void WandLog::writePlot(const std::filesystem::path& svg, const std::string& title) const {
  TrajectoryPlot plot = plot_;
  plot.title = title;
  writeTrajectoryPlot(svg, plot);
}

}  // namespace gb
