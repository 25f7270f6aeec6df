#pragma once
// What a run leaves in its output folder: per-frame stats, meshes, and a summary. Every file is flushed as
// it is written, so a run that stops part-way keeps everything up to its last frame.

#include <filesystem>
#include <fstream>
#include <string>

#include "film.h"
#include "simulation.h"

namespace gb {

// Writes the film's living triangles as binary little-endian PLY: vertex x y z, thickness (m) and air flow
// strength (m^3/s) per vertex, faces as vertex lists.
void writePly(const std::filesystem::path& path, const Film& film);

// The aerosol droplets as a binary PLY point cloud: x y z (m), mass (kg), age (s).
void writeAerosolPly(const std::filesystem::path& path, const Aerosol& aerosol);

// stats.csv: one row per frame.
class StatsWriter {
 public:
  explicit StatsWriter(const std::filesystem::path& path);
  void write(long frame, const FrameStats& stats, int substeps, double frameMilliseconds, const std::string& events);

 private:
  std::ofstream out_;
};

}  // namespace gb
