#include "evaluate_command.h"

#include <cstdio>

#include "cli_checks.h"
#include "depth_recording.h"
#include "hand_evaluation.h"
#include "input_options.h"
#include "trajectory_file.h"
#include "untrusted.h"

namespace gb {

namespace {

void printHeader() {
  std::printf("%-24s %7s %8s %8s %12s %9s %10s %9s\n", "recording", "frames", "<=10 cm", "<=15 cm", "false/frame",
              "swapped", "median cm", "ms/frame");
}

// The median error of the hands found, "-" when none was (a median of nothing is no 0.0 cm).
std::string medianText(const HandScore& s) {
  if (s.within15 == 0) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", 100 * s.medianError());
  return text;
}

void printScore(const std::string& name, const HandScore& s) {
  std::printf("%-24s %7ld %7.1f%% %7.1f%% %12.3f %8.1f%% %10s %9.1f\n", printable(name).c_str(), s.frames,
              100 * s.found10(), 100 * s.found15(), s.falsePerFrame(), 100 * s.swappedShare(), medianText(s).c_str(),
              s.msPerFrame());
}

}  // namespace

CLI::App* addEvaluateCommand(CLI::App& app, EvaluateOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "evaluate", "score the hands found in depth recordings against their ground truth (hands.csv)");
  cmd->add_option("recordings", o.recordings, "fakenect recordings: folders or .tar.gz archives of one")->required();
  cmd->add_option("--truth", o.truth, "the ground truth of a single recording (a trajectory CSV), if not hands.csv")
      ->check(NotEmpty());
  addDepthBandOption(cmd, o.depthBand);
  cmd->add_flag("--mirrored", o.mirrored, "the depth images are mirrored (the performer's left hand on the left)");
  cmd->add_option("--forest", o.forest, "a hand forest model (gb_train_hand_forest) instead of the built-in one")
      ->check(NotEmpty());
  cmd->add_flag("--each", o.perRecording, "print a line per recording, not only the total");
  return cmd;
}

int runEvaluate(const EvaluateOptions& o) {
  if (!o.truth.empty() && o.recordings.size() != 1) {
    std::fprintf(stderr, "error: --truth gives the ground truth of one recording; %zu were given\n",
                 o.recordings.size());
    return 1;
  }
  if (o.depthBand[0] >= o.depthBand[1]) {
    std::fprintf(stderr, "error: --depth-band: expected NEAR FAR with NEAR < FAR\n");
    return 1;
  }
  DetectionOptions detection;
  detection.segmentation.nearLimit = static_cast<float>(o.depthBand[0]);
  detection.segmentation.farLimit = static_cast<float>(o.depthBand[1]);
  HandForest forest;
  if (!o.forest.empty()) {
    try {
      forest = readHandForest(o.forest);
    } catch (const std::runtime_error& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
    detection.forest = &forest;
  }
  TrackerOptions tracker;
  tracker.mirrored = o.mirrored;
  HandScore total;
  if (o.perRecording) printHeader();
  try {
    for (const std::string& path : o.recordings) {
      DepthRecording recording = readDepthRecording(path);
      if (!o.truth.empty()) recording.truth = readTrajectory(o.truth);
      const HandScore score = evaluateRecording(recording, detection, tracker);
      if (o.perRecording) printScore(recording.name, score);
      total += score;
    }
  } catch (const HandSourceError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  if (!o.perRecording) printHeader();
  if (!o.perRecording || o.recordings.size() > 1) printScore("all " + std::to_string(o.recordings.size()), total);
  return 0;
}

}  // namespace gb
