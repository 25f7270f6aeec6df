#pragma once
// What a run leaves in its output folder: per-frame stats, meshes, and a summary. Whole files are written
// atomically and rows are checked as they are written (output_file.h), so a run that stops part-way keeps
// everything up to its last frame and a full disk stops the run with an OutputError naming the file.

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/outputs/step_render_overlap.h"
#include "capture/output_file.h"
#include "model/film.h"
#include "simulation/simulation.h"

namespace gb {

// Writes the film's living triangles as binary little-endian PLY: vertex x y z, thickness (m) and air flow
// strength (m^3/s) per vertex, faces as vertex lists.
void writePly(const std::filesystem::path& path, const Film& film);

// The aerosol droplets as a binary PLY point cloud: x y z (m), mass (kg), age (s).
void writeAerosolPly(const std::filesystem::path& path, const Aerosol& aerosol);

// The whole run in figures, for stats.json and the Table 1 summary: averages over frames, and the events.
class RunRecord {
 public:
  void start(const FrameStats& first);  // the new film, before any frame ran
  void addFrame(const FrameStats& stats, int substeps, double frameMilliseconds, const std::string& events);
  // The performer's touch that burst the film this frame (Simulation::lastTouch): stats.json's burst_by_touch event
  // carries where and how fast.
  void addTouch(double time, const Touch& touch) { touches_.emplace_back(time, touch); }
  // stats.json: the scene, status ("finished", "interrupted" or why it stopped), frames, averages as in Table 1
  // of the paper over the frames with a film, the first and last frame's figures, every event with its time and
  // the notes. Written whole, atomically (a temporary file renamed), so a reader never sees half of it.
  void writeJson(const std::filesystem::path& path, const std::string& scene, const std::string& status) const;
  // Simulated seconds per wall second of the run (1: real time), for stats.json.
  void setRealTimeFactor(double factor) { realTimeFactor_ = factor; }
  // What the implicit step's energy budget did (Simulation::energyBudgetRecord), for stats.json and the summary.
  void setEnergyBudget(const Simulation::BudgetRecord& budget) { budget_ = budget; }
  // What the frames read back from the device (Simulation::readbackRecord), for stats.json's "readback" and the
  // summary.
  void setReadback(const Simulation::ReadbackRecord& readback) { readback_ = readback; }
  // How long the step and the render were busy, and both at once, over `wall` seconds (a rendered run): stats.json's
  // "step_render_overlap" and the summary.
  void setOverlap(const StepRenderOverlap::Totals& overlap, double wall) {
    overlap_ = overlap;
    overlapWall_ = wall;
  }
  // "step and render overlap  0.92 s of 6.10 s wall (15%); step 4.10 s, render 3.20 s"; nothing for a run
  // without a render.
  void printOverlap() const;
  // A string field of stats.json beside the figures, e.g. "video_error".
  void note(const std::string& key, const std::string& value);
  // Adds `milliseconds` of this frame to the phase `name` ("step", "render"...): stats.json's "phase_ms" and the
  // summary's line give each phase's mean per frame, in the order first added.
  void addPhase(const std::string& name, double milliseconds);
  // "ms per frame by phase: step 3.1, contacts 8.0, ..." (nothing before any frame).
  void printPhases() const;
  // The paper's Table 1 row for this run: example, average particles, average triangles, average frames/s.
  void printTable1(const std::string& scene) const;
  // The summary's two lines on the film: its events in order, in words ("pinched off 1.86 s, burst 6.72 s
  // (touched the floor)", film growth counted rather than listed), and its largest area, volume, particles and
  // droplet cloud. A run's last frame alone says little: the default performance ends with the film gone.
  [[nodiscard]] std::string story() const;

 private:
  long frames_ = 0;
  long filmFrames_ = 0;  // frames with a film (particles > 0): what Table 1 averages
  std::vector<std::pair<std::string, std::string>> extra_;
  double particleSum_ = 0, triangleSum_ = 0, millisecondSum_ = 0, substepSum_ = 0;
  FrameStats first_, last_;
  FrameStats largestArea_, largestVolume_;  // the frames with the largest area and |volume|
  size_t mostParticles_ = 0, mostDroplets_ = 0;
  double realTimeFactor_ = 0;
  Simulation::BudgetRecord budget_;
  Simulation::ReadbackRecord readback_;
  std::optional<StepRenderOverlap::Totals> overlap_;
  double overlapWall_ = 0;
  std::vector<std::pair<double, std::string>> events_;
  std::vector<std::pair<double, Touch>> touches_;
  std::vector<std::pair<std::string, double>> phaseSums_;  // ms over all frames
};

// stats.json while a run goes on ("status": "running"): the folder's files are being rewritten and are no run's whole
// result. Replaced by the run's own stats.json when it ends, or left so by a run killed outright (a second Ctrl-C).
void markRunning(const std::filesystem::path& path, const std::string& scene);

// Pokes the film at its top (Simulation::topParticle), as --burst-at and the live window's B do. False when there is
// no film to poke: after a burst its particles linger dead until the next dip.
bool pokeTop(Simulation& sim);

// A frame's topology events as the words of stats.csv and OSC (burst_started burst_finished pinched_off
// film_grown), space-separated; empty when nothing happened.
std::string describeEvents(const TopologyEvents& events);

// stats.csv: one row per frame, each checked (OutputError naming the file when it cannot be written).
class StatsWriter {
 public:
  explicit StatsWriter(const std::filesystem::path& path);
  // `touch`: the performer's touch that burst the film this frame, if any (its position in the touch_*_m columns).
  void write(long frame, const FrameStats& stats, int substeps, double frameMilliseconds, const std::string& events,
             const std::optional<Touch>& touch = std::nullopt);
  void close();

 private:
  RowFile out_;
};

}  // namespace gb
