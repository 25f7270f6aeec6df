// gb_hands_bench: the hand finder judged on real Kinect depth with ground-truth hands (../shared/real-depth:
// UTD-MHAD, 191 recordings), as recorded and composited into rooms (tests/depth_composite.h), with the figures
// of `giantbubble evaluate`: true hands found within 10 and 15 cm, false hands per frame, swapped frames,
// detection time. The tables of docs/capture.md ("Judged on real depth") come from it.
//
//   ./build/bench/gb_hands_bench                       # every recording, every variant
//   ./build/bench/gb_hands_bench --limit 20 --variants recorded,close
//   ./build/bench/gb_hands_bench --png out/composites  # depth plots of a frame of each variant
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>

#include "capture/depth_plot.h"
#include "capture/hand_evaluation.h"
#include "tests/depth_composite.h"
#include "tests/synthetic_depth.h"

#ifndef GB_REAL_DEPTH_DIR
#define GB_REAL_DEPTH_DIR "../shared/real-depth/utd-mhad"
#endif

namespace {

namespace fs = std::filesystem;
using gb::test::CompositeOptions;

struct Variant {
  std::string name;
  bool recorded = false;  // the recording as it is, background removed
  CompositeOptions composite;
  bool bystander = false;
};

// The rooms a performer meets: the recording as it is, then the same people in rooms, stepping in or there
// from the first frame, near and tilted down (head and feet cut off) or far, with someone else at the edge.
std::vector<Variant> variants() {
  std::vector<Variant> v;
  v.push_back({"recorded", true, {}, false});
  v.push_back({"living-room, steps in", false, {"living-room", 0.0, 0.0, 30, nullptr, 1}, false});
  v.push_back({"office, from the start, bystander", false, {"office", 0.0, 0.0, 0, nullptr, 2}, true});
  v.push_back({"close-wall, 1.2 m, tilt 13", false, {"close-wall", 1.2, 13.0, 0, nullptr, 3}, false});
  v.push_back({"living-room, 1.8 m, tilt 13", false, {"living-room", 1.8, 13.0, 0, nullptr, 4}, false});
  v.push_back({"office, 3.8 m, steps in", false, {"office", 3.8, 0.0, 30, nullptr, 5}, false});
  return v;
}

// aA_sS_tT: the action (1-27) and the subject.
std::pair<int, int> actionAndSubject(const std::string& name) {
  std::smatch m;
  static const std::regex pattern("a([0-9]+)_s([0-9]+)_t[0-9]+");
  if (!std::regex_search(name, m, pattern)) return {0, 0};
  return {std::stoi(m[1]), std::stoi(m[2])};
}

// The actions in which both hands move (the others move the right hand; the left hangs at the side).
bool bothHandsMove(int action) {
  return action == 4 || action == 6 || action == 13 || action == 16 || action == 18 || action == 27;
}

void printRow(const std::string& name, const gb::HandScore& s) {
  std::printf("%-36s %7ld %7.1f%% %7.1f%% %11.3f %8.2f%% %9.1f %8.1f\n", name.c_str(), s.frames, 100 * s.found10(),
              100 * s.found15(), s.falsePerFrame(), 100 * s.swappedShare(), 100 * s.medianError(), s.msPerFrame());
}

void printHeader(const char* first) {
  std::printf("%-36s %7s %8s %8s %11s %9s %9s %8s\n", first, "frames", "<=10 cm", "<=15 cm", "false/frm", "swapped",
              "med. cm", "ms/frm");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gb_hands_bench: hands found on real Kinect depth with ground truth, as recorded and in rooms"};
  std::string data = GB_REAL_DEPTH_DIR, forestFile, png, only;
  std::vector<std::string> chosen;
  int limit = 0;
  app.add_option("--data", data, "folder of recording archives with hands.csv (UTD-MHAD)");
  app.add_option("--limit", limit, "every n-th recording only, for n = total / limit (0: all)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--variants", chosen, "which variants (names' first words: recorded, living-room, office, close)")
      ->delimiter(',');
  app.add_option("--only", only, "recordings whose name contains this");
  app.add_option("--png", png, "write depth plots of each variant's middle frame into this folder");
  app.add_option("--forest", forestFile, "a hand forest model (gb_train_hand_forest) instead of the built-in one");
  CLI11_PARSE(app, argc, argv);

  std::vector<fs::path> archives;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(data, ec))
    if (gb::isRecordingArchive(entry.path()) && entry.path().string().find(only) != std::string::npos)
      archives.push_back(entry.path());
  if (archives.empty()) {
    std::fprintf(stderr, "error: no recording archives (*.tar.gz) in %s\n", data.c_str());
    return 1;
  }
  std::sort(archives.begin(), archives.end());
  if (limit > 0 && static_cast<int>(archives.size()) > limit) {
    std::vector<fs::path> every;
    for (size_t i = 0; i < archives.size(); i += archives.size() / static_cast<size_t>(limit))
      every.push_back(archives[i]);
    archives = every;
  }
  std::vector<Variant> all = variants(), run;
  for (const Variant& v : all) {
    bool take = chosen.empty();
    for (const std::string& c : chosen) take = take || v.name.rfind(c, 0) == 0;
    if (take) run.push_back(v);
  }
  if (!png.empty()) fs::create_directories(png);

  std::map<std::string, gb::HandScore> byVariant, byGroup;
  gb::DetectionOptions detection;
  gb::TrackerOptions tracker;
  gb::HandForest forest;
  if (!forestFile.empty()) {
    try {
      forest = gb::readHandForest(forestFile);
    } catch (const std::runtime_error& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
    detection.forest = &forest;
  }
  std::optional<gb::DepthRecording> previous;  // the bystander: another subject's recording
  for (const fs::path& archive : archives) {
    gb::DepthRecording recording;
    try {
      recording = gb::readDepthRecording(archive);
    } catch (const gb::HandSourceError& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
    const auto [action, subject] = actionAndSubject(recording.name);
    for (Variant& v : run) {
      gb::DepthRecording played;
      if (v.recorded) {
        played = recording;
      } else {
        v.composite.bystander = v.bystander && previous ? &*previous : nullptr;
        played = gb::test::composite(recording, v.composite);
      }
      const gb::HandScore score = gb::evaluateRecording(played, detection, tracker);
      byVariant[v.name] += score;
      byGroup[std::string(bothHandsMove(action) ? "both hands move" : "right hand moves, left hangs") + ", " +
              (v.recorded ? "recorded" : "rooms")] += score;
      if (!png.empty() && archive == archives.front()) {
        gb::HandFinder finder(detection, tracker);
        gb::HandSample hands;
        const size_t middle = played.frames.size() / 2;
        for (size_t i = 0; i <= middle; ++i) hands = finder.update(played.frames[i]);
        std::string file = v.name;
        for (char& c : file)
          if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        gb::writeDepthPlot((fs::path(png) / (file + ".png")).string(), played.frames[middle], finder.detection(),
                           hands);
      }
    }
    if (!previous || actionAndSubject(previous->name).second != subject) previous = std::move(recording);
  }
  std::printf("%zu recordings of %s\n\n", archives.size(), data.c_str());
  printHeader("variant");
  gb::HandScore total;
  for (const Variant& v : run) {
    printRow(v.name, byVariant[v.name]);
    total += byVariant[v.name];
  }
  printRow("all", total);
  std::printf("\n");
  printHeader("actions");
  for (const auto& [name, score] : byGroup) printRow(name, score);
  return 0;
}
