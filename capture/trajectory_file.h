#pragma once
// Hand trajectories as CSV (docs/formats.md): a header `t,left_x,left_y,left_z,right_x,right_y,right_z`, then one
// row per sample in camera space (seconds, metres). A hand left empty (three empty fields) was not measured in
// that row. Lines starting with # are comments.

#include <cstdio>
#include <filesystem>
#include <vector>

#include "hand_source.h"

namespace gb {

// Reads a whole file; throws HandSourceError naming the file, the line and the problem. Hands missing from a
// row are held (HandHold) from their last measured position.
std::vector<HandSample> readTrajectory(const std::filesystem::path& path, double holdTime = 0.5);

class TrajectoryWriter {
 public:
  explicit TrajectoryWriter(const std::filesystem::path& path);  // throws HandSourceError when it cannot
  ~TrajectoryWriter();
  TrajectoryWriter(const TrajectoryWriter&) = delete;  // owns the open file
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;
  // Writes a row; a hand not measured in this sample (held or never seen) is written as missing.
  void write(const HandSample& sample);

 private:
  std::FILE* file_ = nullptr;
};

}  // namespace gb
