#pragma once
// How smooth and how late a wand trajectory is, for the stabilizer tests and `giantbubble record --report`.

#include <vector>

#include "capture/hand_source.h"

namespace gb {

// Jitter: RMS of the second difference x_{i+1} - 2 x_i + x_{i-1} of a uniformly sampled trajectory (m).
double jitter(const std::vector<Vec3d>& positions);

// Lag (s) of `follower` behind `leader`, both sampled at the same uniform times dt apart: the shift in
// [0, maxLag] that minimises the RMS distance between follower(t) and leader(t - shift) (linear interpolation,
// dt / 20 resolution). `rmsError`, when given, receives that smallest RMS distance (m).
double lag(const std::vector<Vec3d>& leader, const std::vector<Vec3d>& follower, double dt, double maxLag,
           double* rmsError = nullptr);

}  // namespace gb
