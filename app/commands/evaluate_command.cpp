#include "app/commands/evaluate_command.h"

#include <cstdio>
#include <map>

#include "app/commands/cli_checks.h"
#include "app/commands/film_evaluation.h"
#include "app/commands/input_options.h"
#include "capture/depth_recording.h"
#include "capture/hand_evaluation.h"
#include "capture/trajectory_file.h"
#include "capture/untrusted.h"
#include "scene/scene_file.h"

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

void printFilmHeader() {
  std::printf("%-24s %6s %9s %9s %8s %8s %8s  %s\n", "recording", "films", "survived", "life", "growth", "lag ms",
              "m/s", "how the films ended");
}

void printFilmLine(const std::string& name, const std::vector<FilmLife>& lives) {
  const FilmLifeSummary s = summarize(lives);
  std::map<std::string, int> endings;
  double fastest = 0;
  for (const FilmLife& l : lives) {
    ++endings[l.pinchedOff ? "pinched off" : l.burstCause.empty() ? "whole" : "burst: " + l.burstCause];
    fastest = std::max(fastest, l.peakWandSpeed);
  }
  std::string ended;
  for (const auto& [how, count] : endings) ended += (ended.empty() ? "" : ", ") + how + " " + std::to_string(count);
  std::printf("%-24s %6zu %8.0f%% %8.0f%% %7.2fx %8.0f %8.1f  %s\n", printable(name).c_str(), s.recordings,
              100 * s.survivedShare, 100 * s.medianLifeShare, s.medianGrowth, 1e3 * s.medianLag, fastest,
              ended.c_str());
}

// The recordings' names up to their first '_' (UTD-MHAD's aA_sS_tT: the action), in the order first met.
std::string groupOf(const std::string& name) { return name.substr(0, name.find('_')); }

int evaluateFilms(const EvaluateOptions& o, const FilmEvaluationOptions& film) {
  std::vector<FilmLife> all;
  std::vector<std::string> order;
  std::map<std::string, std::vector<FilmLife>> groups;
  if (o.perRecording) printFilmHeader();
  for (const std::string& path : o.recordings) {
    const DepthRecording recording = readDepthRecording(path);
    const FilmLife life = playFilmOnRecording(recording, film);
    if (o.perRecording) printFilmLine(recording.name, {life});
    const std::string group = groupOf(recording.name);
    if (!groups.count(group)) order.push_back(group);
    groups[group].push_back(life);
    all.push_back(life);
  }
  std::printf("\n");
  printFilmHeader();
  if (order.size() > 1)
    for (const std::string& group : order) printFilmLine(group, groups[group]);
  printFilmLine("all " + std::to_string(all.size()), all);
  return 0;
}

const char* kindName(TouchTrialKind kind) { return kind == TouchTrialKind::Reach ? "reach" : "away"; }

void printTouchLine(const TouchTrial& t) {
  char burst[64] = "-";
  if (t.touchBurst) std::snprintf(burst, sizeof burst, "%.2f", *t.touchBurst);
  char entry[32] = "-";
  if (t.kind == TouchTrialKind::Reach) std::snprintf(entry, sizeof entry, "%.2f", t.entry);
  std::printf("%-24s %6s %8s %8s %8s  %s%s\n", printable(t.recording).c_str(), kindName(t.kind), entry, burst,
              t.passed() ? "yes" : "no", t.otherBurst.empty() ? "" : "burst first by: ", t.otherBurst.c_str());
}

// `evaluate --touch`: each recording of a judged action against its still bubble, and the shares that passed.
int evaluateTouches(const EvaluateOptions& o, const FilmEvaluationOptions& film) {
  std::map<TouchTrialKind, std::pair<int, int>> passed;  // kind: passed, trials
  if (o.perRecording) std::printf("%-24s %6s %8s %8s %8s\n", "recording", "bubble", "entry s", "touch s", "passed");
  for (const std::string& path : o.recordings) {
    const DepthRecording recording = readDepthRecording(path);
    if (!touchTrialKindOf(recording.name)) {
      std::fprintf(stderr, "note: %s: not an action the touch is judged on; skipped\n", recording.name.c_str());
      continue;
    }
    const TouchTrial trial = playTouchOnRecording(recording, film);
    if (o.perRecording) printTouchLine(trial);
    auto& [yes, all] = passed[trial.kind];
    yes += trial.passed() ? 1 : 0;
    ++all;
  }
  const auto share = [&](TouchTrialKind kind) {
    const auto [yes, all] = passed[kind];
    return all > 0 ? 100.0 * yes / all : 0.0;
  };
  std::printf("\nreach (push, punch, knock): burst by the touch on time in %d of %d (%.1f%%; target >= 90%%)\n",
              passed[TouchTrialKind::Reach].first, passed[TouchTrialKind::Reach].second, share(TouchTrialKind::Reach));
  const auto [awayPassed, away] = passed[TouchTrialKind::Away];
  std::printf("away (wave, clap, circle): burst by a touch in %d of %d (%.1f%%; target <= 2%%)\n", away - awayPassed,
              away, away > 0 ? 100.0 * (away - awayPassed) / away : 0.0);
  return 0;
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
  cmd->add_flag("--film", o.film,
                "play each recording's hands into a run of --scene and say what the film did: the share that lived "
                "to the end or pinched off, the median life (share of the recording), growth (peak area over the "
                "start) and the wands' lag");
  cmd->add_flag("--touch", o.touch,
                "place a still bubble (radius 0.15 m) in each recording by its ground truth and play the depth's body "
                "against it: at the farthest-forward true hand of a push, punch or knock it must burst by the touch "
                "from 0.3 s before to 0.2 s after the hand enters it; 0.5 m from every true hand of a wave, clap or "
                "circle it must not")
      ->excludes("--film");
  cmd->add_flag("--truth-hands", o.truthHands, "--film: the ground truth's hands move the wands, not those found");
  cmd->add_option("--scene", o.scene, "--film: the scene (a built-in name or a .toml file)")->check(NotEmpty());
  cmd->add_option("--stabilizer", o.stabilizer, "--film: the hand stabilizer")
      ->check(CLI::IsMember({"bspline", "one-euro"}));
  cmd->add_option("--reach", o.reach, "--film: world metres per metre of hand motion")->check(FiniteRange(0.1, 20.0));
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
  if (o.film || o.touch) {
    try {
      FilmEvaluationOptions film{resolveScene(o.scene).run, detection, tracker, o.truthHands};
      film.run.input.stabilizer = o.stabilizer;
      film.run.input.reach = o.reach;
      return o.touch ? evaluateTouches(o, film) : evaluateFilms(o, film);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
  }
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
