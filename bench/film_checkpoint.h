#pragma once
// A film and the wands holding it, written to a binary file and read back, so that a long stress run can be
// resumed near an event instead of stepping the thousands of frames before it again (bench/stress_bench.cpp's
// --checkpoint and --resume). The file is this program's own: raw little-endian arrays, no versioning; it is
// read only by the build that wrote it. Every per-particle array and the topology are kept; the per-triangle
// geometry, contacts and colouring are derived again by the Simulation that takes the film.

#include <array>
#include <string>

#include "model/film.h"

namespace gb {

struct FilmCheckpoint {
  Film film;
  WandState wands;
  std::array<bool, 2> wandsArmed{true, true};  // Simulation::wandsArmed
  int frame = 0;                               // the frame the film was written after
  std::string randomWands;  // the wand generator's state, as its own text (std::mt19937 and two velocities)
};

// Throws std::runtime_error naming the file when it cannot be written or read, or is not a checkpoint.
void writeCheckpoint(const std::string& path, const FilmCheckpoint& checkpoint);
FilmCheckpoint readCheckpoint(const std::string& path);

}  // namespace gb
