#pragma once
// The input hand trajectories against the stabilized wand trajectories, as in the paper's Figure 4 and the
// side panels of Figure 10: one column per hand (left red, right blue), a front view (x right, y up) above a
// top view (x right, z forward, the stroke direction), input dotted, wand solid, start +, end x; below them a
// front and a top view of the whole scene, both wands in one frame with the floor (y = 0), the world's origin
// and, for a camera or a recorded input, the camera, to see where the performance took place. SVG.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model/state.h"

namespace gb {

struct TrajectoryPlot {
  std::string title;
  std::vector<Vec3> leftInput, rightInput;  // world space; a NaN point is a gap (hand not measured)
  std::vector<Vec3> leftWand, rightWand;    // world space
  std::optional<Vec3> camera;               // the camera's position in world space, when there is one
};

// Written atomically; OutputError naming the file and the reason when it cannot be (output_file.h).
void writeTrajectoryPlot(const std::filesystem::path& path, const TrajectoryPlot& plot);

}  // namespace gb
