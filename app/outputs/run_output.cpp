#include "app/outputs/run_output.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace gb {

namespace {

template <class T>
void writeRaw(std::string& out, T value) {
  static_assert(std::endian::native == std::endian::little, "PLY writer assumes a little-endian host");
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

}  // namespace

void writePly(const std::filesystem::path& path, const Film& film) {
  const State& s = film.state;
  const Topology& topo = film.topology;
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment giantbubble film\nelement vertex " +
                    std::to_string(s.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\n"
                    "property float thickness\nproperty float air_flow\nelement face " +
                    std::to_string(topo.triangleCount()) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  out.reserve(out.size() + s.size() * 5 * sizeof(float) + topo.triangleCount() * (1 + 3 * sizeof(uint32_t)));
  for (size_t i = 0; i < s.size(); ++i) {
    writeRaw(out, s.position.x[i]);
    writeRaw(out, s.position.y[i]);
    writeRaw(out, s.position.z[i]);
    writeRaw(out, s.thickness[i]);
    writeRaw(out, s.airFlow.get(i).norm());
  }
  for (size_t t = 0; t < topo.triangleCount(); ++t) {
    writeRaw(out, static_cast<uint8_t>(3));
    for (int c = 0; c < 3; ++c) writeRaw(out, topo.triangles[3 * t + c]);
  }
  writeFileAtomically(path, out);
}

void writeAerosolPly(const std::filesystem::path& path, const Aerosol& aerosol) {
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment giantbubble aerosol droplets\nelement vertex " +
                    std::to_string(aerosol.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty float mass\n"
                    "property float age\nend_header\n";
  for (size_t i = 0; i < aerosol.size(); ++i) {
    writeRaw(out, aerosol.position.x[i]);
    writeRaw(out, aerosol.position.y[i]);
    writeRaw(out, aerosol.position.z[i]);
    writeRaw(out, aerosol.mass[i]);
    writeRaw(out, aerosol.age[i]);
  }
  writeFileAtomically(path, out);
}

StatsWriter::StatsWriter(const std::filesystem::path& path) : out_(path) {
  out_.write(
      "frame,time_s,particles,triangles,area_m2,volume_m3,kinetic_J,elastic_J,potential_J,liquid_m3,"
      "mean_thickness_m,max_speed_mps,mean_air_flow_m3ps,solution,droplets,droplet_mass_kg,substeps,frame_ms,"
      "touch_x_m,touch_y_m,touch_z_m,events\n");
}

void StatsWriter::write(long frame, const FrameStats& st, int substeps, double frameMilliseconds,
                        const std::string& events, const std::optional<Touch>& touch) {
  std::ostringstream row;
  row << frame << ',' << st.time << ',' << st.particles << ',' << st.triangles << ',' << st.area << ',' << st.volume
      << ',' << st.kineticEnergy << ',' << st.elasticEnergy << ',' << st.potentialEnergy << ',' << st.liquid << ','
      << st.meanThickness << ',' << st.maxSpeed << ',' << st.meanAirFlow << ',' << st.solution << ',' << st.droplets
      << ',' << st.dropletMass << ',' << substeps << ',' << frameMilliseconds << ',';
  if (touch)
    row << touch->position.x() << ',' << touch->position.y() << ',' << touch->position.z();
  else
    row << ",,";
  row << ',' << events << '\n';
  out_.write(row.str());
}

void StatsWriter::close() { out_.close(); }

void RunRecord::start(const FrameStats& first) {
  first_ = last_ = largestArea_ = largestVolume_ = first;
  mostParticles_ = first.particles;
  mostDroplets_ = first.droplets;
  events_.emplace_back(first.time, "film_created");
}

void RunRecord::addFrame(const FrameStats& stats, int substeps, double frameMilliseconds, const std::string& events) {
  last_ = stats;
  ++frames_;
  if (stats.area > largestArea_.area) largestArea_ = stats;
  if (std::abs(stats.volume) > std::abs(largestVolume_.volume)) largestVolume_ = stats;
  mostParticles_ = std::max(mostParticles_, stats.particles);
  mostDroplets_ = std::max(mostDroplets_, stats.droplets);
  std::istringstream words(events);
  for (std::string event; words >> event;) events_.emplace_back(stats.time, event);
  // Table 1 averages a performance with a film: frames after the film is gone (droplets alone) would drag
  // the particle and triangle counts towards zero and the frame rate up.
  if (stats.particles == 0) return;
  ++filmFrames_;
  particleSum_ += static_cast<double>(stats.particles);
  triangleSum_ += static_cast<double>(stats.triangles);
  millisecondSum_ += frameMilliseconds;
  substepSum_ += substeps;
}

namespace {

nlohmann::json frameJson(const FrameStats& s) {
  return {{"time_s", s.time},
          {"particles", s.particles},
          {"triangles", s.triangles},
          {"area_m2", s.area},
          {"volume_m3", s.volume},
          {"liquid_m3", s.liquid},
          {"solution", s.solution},
          {"droplets", s.droplets},
          {"kinetic_J", s.kineticEnergy},
          {"mean_thickness_m", s.meanThickness}};
}

}  // namespace

void RunRecord::writeJson(const std::filesystem::path& path, const std::string& scene,
                          const std::string& status) const {
  const double n = static_cast<double>(std::max(filmFrames_, 1L));
  const double msPerFrame = millisecondSum_ / n;
  nlohmann::json j;
  j["scene"] = scene;
  j["status"] = status;
  j["frames"] = frames_;
  j["frames_with_film"] = filmFrames_;
  j["average"] = {{"particles", particleSum_ / n},
                  {"triangles", triangleSum_ / n},
                  {"frame_ms", msPerFrame},
                  {"frames_per_second", msPerFrame > 0 ? 1e3 / msPerFrame : 0.0},
                  {"substeps_per_frame", substepSum_ / n},
                  {"step_ms", substepSum_ > 0 ? millisecondSum_ / substepSum_ : 0.0}};
  j["real_time_factor"] = realTimeFactor_;
  j["energy_budget"] = {{"frames", budget_.frames},
                        {"smallest_factor", budget_.smallestScale},
                        {"largest_drift_given_back_mps", budget_.largestShift}};
  const auto perFrame = [](uint64_t bytes, long frames) {
    return frames > 0 ? static_cast<double>(bytes) / static_cast<double>(frames) : 0.0;
  };
  if (overlap_) {
    const auto timed = [&](double seconds) { return overlap_->renderTimed ? nlohmann::json(seconds) : nullptr; };
    j["step_render_overlap"] = {{"wall_s", overlapWall_},
                                {"step_s", overlap_->step},
                                {"render_s", timed(overlap_->render)},
                                {"both_s", timed(overlap_->both)}};
  }
  j["readback"] = {
      {"state_readbacks", readback_.stateReadbacks},
      {"frames", readback_.frames},
      {"frames_without_event", readback_.framesWithoutEvent},
      {"frames_passed_by_checks", readback_.framesPassed},
      {"frames_held_by_rule", readback_.framesHeldByRule},
      {"state_readbacks_held_by_rule", readback_.stateReadbacksHeldByRule},
      {"bytes_held_by_rule", readback_.bytesHeldByRule},
      {"bytes_per_frame", perFrame(readback_.bytes, readback_.frames)},
      {"bytes_per_frame_without_event", perFrame(readback_.bytesWithoutEvent, readback_.framesWithoutEvent)}};
  j["first_frame"] = frameJson(first_);
  j["last_frame"] = frameJson(last_);
  j["largest"] = {{"area_m2", largestArea_.area},       {"area_time_s", largestArea_.time},
                  {"volume_m3", largestVolume_.volume}, {"volume_time_s", largestVolume_.time},
                  {"particles", mostParticles_},        {"droplets", mostDroplets_}};
  nlohmann::json events = nlohmann::json::array();
  for (const auto& [time, name] : events_) {
    nlohmann::json event = {{"time_s", time}, {"event", name}};
    if (name == "burst_by_touch")  // where the performer touched it, and how fast they closed on each other
      for (const auto& [touchTime, touch] : touches_)
        if (touchTime == time) {
          event["position_m"] = {touch.position.x(), touch.position.y(), touch.position.z()};
          event["approach_mps"] = touch.approachSpeed;
        }
    events.push_back(event);
  }
  j["events"] = events;
  nlohmann::json phases = nlohmann::json::object();
  for (const auto& [name, sum] : phaseSums_) phases[name] = sum / static_cast<double>(std::max(frames_, 1L));
  j["phase_ms"] = phases;
  for (const auto& [key, value] : extra_) j[key] = value;
  writeFileAtomically(path, j.dump(2) + '\n');
}

void markRunning(const std::filesystem::path& path, const std::string& scene) {
  const nlohmann::json j = {{"scene", scene}, {"status", "running"}};
  writeFileAtomically(path, j.dump(2) + '\n');
}

void RunRecord::note(const std::string& key, const std::string& value) { extra_.emplace_back(key, value); }

void RunRecord::addPhase(const std::string& name, double milliseconds) {
  auto phase = std::find_if(phaseSums_.begin(), phaseSums_.end(), [&](const auto& p) { return p.first == name; });
  if (phase == phaseSums_.end())
    phaseSums_.emplace_back(name, milliseconds);
  else
    phase->second += milliseconds;
}

void RunRecord::printPhases() const {
  if (frames_ == 0) return;
  std::string line;
  for (const auto& [name, sum] : phaseSums_) {
    char figure[64];
    std::snprintf(figure, sizeof figure, "%s%s %.1f", line.empty() ? "" : ", ", name.c_str(),
                  sum / static_cast<double>(frames_));
    line += figure;
  }
  std::printf("%-28s %s\n", "ms per frame by phase", line.c_str());
}

void RunRecord::printOverlap() const {
  if (overlap_) std::printf("%-28s %s\n", "step and render overlap", describeOverlap(*overlap_, overlapWall_).c_str());
}

void RunRecord::printTable1(const std::string& scene) const {
  const double n = static_cast<double>(std::max(filmFrames_, 1L));
  const double msPerFrame = millisecondSum_ / n;
  std::printf("\n%-12s %18s %18s %26s\n", "Example", "Avg. Particle Size", "Avg. Triangle Size",
              "Avg. Time (fps) (simulation)");
  std::printf("%-12s %18.0f %18.0f %26.1f\n", scene.c_str(), particleSum_ / n, triangleSum_ / n,
              msPerFrame > 0 ? 1e3 / msPerFrame : 0.0);
}

namespace {

// Why a burst started (BurstFront::cause, the event burst_by_<cause>), in words.
std::string burstCauseInWords(const std::string& cause) {
  if (cause == "thin") return "thinned out";
  if (cause == "floor") return "touched the floor";
  if (cause == "wand") return "touched a wand";
  if (cause == "touch") return "touched by the performer";
  if (cause == "impact") return "hit itself";
  if (cause == "poke") return "poked";
  return cause;
}

// The events after `from` at the same time whose name starts with `prefix`, without it ("" when none).
std::string sameFrameSuffix(const std::vector<std::pair<double, std::string>>& events, size_t from,
                            const std::string& prefix) {
  for (size_t k = from + 1; k < events.size() && events[k].first == events[from].first; ++k)
    if (events[k].second.starts_with(prefix)) return events[k].second.substr(prefix.size());
  return "";
}

std::string seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f s", t);
  return text;
}

}  // namespace

std::string RunRecord::story() const {
  constexpr size_t kMostPhrases = 8;  // a show with many films: the rest is in stats.json
  size_t grown = 0;
  double firstGrown = 0, lastGrown = 0;
  for (const auto& [time, name] : events_)
    if (name == "film_grown") {
      if (grown++ == 0) firstGrown = time;
      lastGrown = time;
    }
  std::vector<std::string> phrases;
  bool growthTold = false;
  for (size_t k = 0; k < events_.size(); ++k) {
    const auto& [time, name] = events_[k];
    if (name == "film_created") {
      phrases.push_back("made " + seconds(time));
    } else if (name == "film_grown" && !growthTold) {
      growthTold = true;
      phrases.push_back("grown at the wire on " + std::to_string(grown) + " frames (" + seconds(firstGrown) + " to " +
                        seconds(lastGrown) + ")");
    } else if (name == "pinched_off") {
      phrases.push_back("pinched off " + seconds(time));
    } else if (name == "burst_started") {
      const std::string cause = sameFrameSuffix(events_, k, "burst_by_");
      phrases.push_back("burst " + seconds(time) + (cause.empty() ? "" : " (" + burstCauseInWords(cause) + ")"));
    } else if (name == "burst_finished") {
      phrases.push_back("gone " + seconds(time));
    } else if (name == "performer_found") {
      phrases.push_back("performer found");
    }
  }
  std::string story;
  for (size_t k = 0; k < std::min(phrases.size(), kMostPhrases); ++k) story += (k ? ", " : "") + phrases[k];
  if (phrases.size() > kMostPhrases)
    story += ", and " + std::to_string(phrases.size() - kMostPhrases) + " more (stats.json)";
  char largest[200];
  std::snprintf(largest, sizeof largest, "area %.4f m^2 (%s), volume %.4f m^3 (%s), %zu particles, %zu droplets",
                largestArea_.area, seconds(largestArea_.time).c_str(), largestVolume_.volume,
                seconds(largestVolume_.time).c_str(), mostParticles_, mostDroplets_);
  char lines[200];
  std::snprintf(lines, sizeof lines, "%-28s ", "film's life");
  std::string text = lines + story + "\n";
  std::snprintf(lines, sizeof lines, "%-28s ", "largest");
  text += lines + std::string(largest) + "\n";
  if (budget_.frames > 0) {  // the step's safeguard acted: say so (docs/model.md "Energy budget")
    std::snprintf(lines, sizeof lines,
                  "%-28s took energy back on %ld of %ld frames (smallest factor on the wobble %.2f, most drift given "
                  "back %.3f m/s)\n",
                  "energy budget", budget_.frames, frames_, budget_.smallestScale, budget_.largestShift);
    text += lines;
  }
  if (readback_.bytes > 0) {  // a device stepper: what its frames copied back (docs/backends.md)
    const auto kib = [](uint64_t bytes, long frames) {
      return frames > 0 ? static_cast<double>(bytes) / 1024.0 / static_cast<double>(frames) : 0.0;
    };
    std::snprintf(lines, sizeof lines,
                  "%-28s the state on %zu of %ld frames (%ld passed by the device's checks); %.1f KiB a frame, "
                  "%.1f KiB on the %ld frames without a topology event\n",
                  "read back from the device", readback_.stateReadbacks, readback_.frames, readback_.framesPassed,
                  kib(readback_.bytes, readback_.frames),
                  kib(readback_.bytesWithoutEvent, readback_.framesWithoutEvent), readback_.framesWithoutEvent);
    text += lines;
    if (!readback_.framesHeldByRule.empty()) {
      std::string held;
      for (const auto& [rule, frames] : readback_.framesHeldByRule) {
        const auto bytes = readback_.bytesHeldByRule.find(rule), states = readback_.stateReadbacksHeldByRule.find(rule);
        char moved[96];
        std::snprintf(moved, sizeof moved, " (the state %zu, %.0f KiB)",
                      states == readback_.stateReadbacksHeldByRule.end() ? size_t{0} : states->second,
                      bytes == readback_.bytesHeldByRule.end() ? 0.0 : static_cast<double>(bytes->second) / 1024.0);
        held += (held.empty() ? "" : ", ") + rule + " " + std::to_string(frames) + moved;
      }
      std::snprintf(lines, sizeof lines, "%-28s %s\n", "frames held by the rule", held.c_str());
      text += lines;
    }
  }
  return text;
}

bool pokeTop(Simulation& sim) {
  const size_t top = sim.topParticle();
  const State& s = sim.film().state;
  if (s.size() == 0 || !s.alive[top] || sim.film().topology.boundary[top]) return false;
  sim.startBurst(top);
  return true;
}

std::string describeEvents(const TopologyEvents& e) {
  std::string words;
  auto add = [&](bool happened, const char* word) {
    if (!happened) return;
    if (!words.empty()) words += ' ';
    words += word;
  };
  add(e.started, "burst_started");
  if (e.started && e.cause != nullptr) add(true, (std::string("burst_by_") + e.cause).c_str());
  add(e.finished, "burst_finished");
  add(e.pinchedOff, "pinched_off");
  add(e.particlesAdded > 0, "film_grown");
  return words;
}

}  // namespace gb
