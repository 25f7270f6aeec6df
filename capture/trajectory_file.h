#pragma once
// Hand trajectories as CSV (docs/formats.md): a header `t,left_x,left_y,left_z,right_x,right_y,right_z`, then one
// row per sample in camera space (seconds, metres). A hand left empty (three empty fields) was not measured in
// that row. Lines starting with # are comments.

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "capture/hand_source.h"
#include "capture/output_file.h"

namespace gb {

// How much of a trajectory is read: a run reads what it runs, and no file, however long, is taken whole.
struct TrajectoryLimits {
  // Seconds after both hands are first in a row (the film is made then); later rows are not read.
  double seconds = std::numeric_limits<double>::infinity();
  std::size_t rows = 1'000'000;  // about 150 MB of samples: 9 hours at 30 per second
};

// The farthest a hand may be from the camera (m): a Kinect sees to about 4 m, and a file in millimetres is refused
// rather than made into wands kilometres apart.
inline constexpr double kMaxHandDistance = 100.0;

// The longest time between two rows (s), as long as a run may last: the hands would hold still through it, and a
// time like 1e308 is a broken file, not an hour's pause.
inline constexpr double kMaxTrajectoryGap = 3600.0;

// The largest trajectory file and line read: 1,000,000 rows of seven numbers are under 150 MB, a row under 200 bytes.
inline constexpr std::uintmax_t kMaxTrajectoryBytes = std::uintmax_t{1} << 30;
inline constexpr std::size_t kMaxTrajectoryLineBytes = 4096;

// Reads a file up to its end or `limits`; throws HandSourceError naming the file, the line and the problem. Hands
// missing from a row are held (HandHold) from their last measured position. When the limits leave rows unread,
// `cut` (if given) gets a note saying so.
std::vector<HandSample> readTrajectory(const std::filesystem::path& path, double holdTime = 0.5,
                                       const TrajectoryLimits& limits = {}, std::string* cut = nullptr);

// A trajectory written as it is recorded: into PATH.partial, renamed over PATH by close() (output_file.h), so that a
// recording that fails leaves the file that was there. Throws OutputError naming the file when it cannot be written.
class TrajectoryWriter {
 public:
  explicit TrajectoryWriter(const std::filesystem::path& path);
  // Writes a row; a hand not measured in this sample (held or never seen) is written as missing.
  void write(const HandSample& sample);
  void close();  // the file is complete: renamed over PATH

 private:
  RowFile file_;
};

}  // namespace gb
