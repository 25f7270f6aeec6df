#include "app/outputs/wand_log.h"

#include <cmath>
#include <cstdio>

namespace gb {

WandLog::WandLog(const std::filesystem::path& csv) : csv_(csv) {
  csv_.write(
      "time_s,left_wand_x,left_wand_y,left_wand_z,right_wand_x,right_wand_y,right_wand_z,"
      "left_wand_vx,left_wand_vy,left_wand_vz,right_wand_vx,right_wand_vy,right_wand_vz,"
      "left_hand_x,left_hand_y,left_hand_z,right_hand_x,right_hand_y,right_hand_z\n");
}

void WandLog::add(double time, const WandFrame& f) {
  std::string row;
  char field[96];
  auto point = [&](const Vec3& v) {
    std::snprintf(field, sizeof field, ",%.5f,%.5f,%.5f", v.x(), v.y(), v.z());
    row += field;
  };
  std::snprintf(field, sizeof field, "%.4f", time);
  row += field;
  for (const Vec3& v : {f.wands.leftPosition, f.wands.rightPosition, f.wands.leftVelocity, f.wands.rightVelocity})
    point(v);
  for (const Vec3& v : {f.leftHand, f.rightHand}) {
    if (v.allFinite())
      point(v);
    else
      row += ",,,";
  }
  row += '\n';
  csv_.write(row);
  plot_.leftWand.push_back(f.wands.leftPosition);
  plot_.rightWand.push_back(f.wands.rightPosition);
  plot_.leftInput.push_back(f.leftHand);
  plot_.rightInput.push_back(f.rightHand);
}

void WandLog::close() { csv_.close(); }

void WandLog::writePlot(const std::filesystem::path& svg, const std::string& title,
                        const std::optional<Vec3>& camera) const {
  TrajectoryPlot plot = plot_;
  plot.title = title;
  plot.camera = camera;
  writeTrajectoryPlot(svg, plot);
}

}  // namespace gb
