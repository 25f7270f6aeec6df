#pragma once
// The floor in a depth frame: the lowest large horizontal layer of points, found along gravity and refined by a
// least-squares plane fit. Gravity comes from the Kinect's accelerometer where a recording carries it, else
// from a search over camera tilts (pitch -10 to 40 degrees down, roll -6 to 6 degrees).
// docs/capture.md describes the method and its limits.

#include <optional>
#include <vector>

#include "capture/hand_source.h"

namespace gb {

struct FloorPlane {
  Vec3d up = Vec3d::UnitY();  // unit normal, pointing away from the floor (camera space)
  double offset = 0.0;        // up . p = offset on the floor
  int inliers = 0;            // points within the fit's tolerance
  [[nodiscard]] double heightOf(const Vec3d& p) const { return up.dot(p) - offset; }
};

// points: camera-space points (any subset of a frame); gravityUp: the direction against gravity in camera
// space, when known. Nothing when no layer holds at least minFraction of the points (no floor in view).
std::optional<FloorPlane> findFloor(const std::vector<Vec3d>& points, const std::optional<Vec3d>& gravityUp,
                                    double minFraction = 0.03);

}  // namespace gb
