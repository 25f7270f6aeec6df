#include "app/commands/film_evaluation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "app/commands/input_options.h"
#include "app/show/performer_touch.h"
#include "capture/trajectory_metrics.h"
#include "simulation/simulation.h"

namespace gb {

namespace {

// The hands a recording's run follows: found in its depth frame by frame, or its ground truth.
std::vector<HandSample> handsOf(const DepthRecording& recording, const FilmEvaluationOptions& o) {
  if (o.truthHands) {
    if (recording.truth.empty()) throw HandSourceError(recording.name + ": no ground truth (hands.csv) to play");
    return recording.truth;
  }
  HandFinder finder(o.detection, o.tracker);
  std::vector<HandSample> samples;
  samples.reserve(recording.frames.size());
  for (const kinect::DepthFrame& frame : recording.frames) samples.push_back(finder.update(frame));
  return samples;
}

// The input a run opens for a camera input: the performer waited for, the calibration centred on them.
std::unique_ptr<StabilizedWands> wandsOf(std::vector<HandSample> samples, const DepthRecording& recording,
                                         const FilmEvaluationOptions& o) {
  InputOptions input = o.run.input;
  input.input = "fakenect:" + recording.name;  // a camera's calibration (the performer found in the depth)
  PerformerWait wait;
  wait.enabled = true;
  wait.say = [](const std::string&) {};
  return std::make_unique<StabilizedWands>(std::make_unique<ReplayHandSource>(std::move(samples), recording.name),
                                           stabilizerOptionsOf(input), calibrationOf(input), wait);
}

float speed(const Vec3& v) { return v.norm(); }

// The lag of the hand that moved more: a hand hanging still has no lag to measure.
double lagOfMovingHand(const std::array<std::vector<Vec3d>, 2>& hands, const std::array<std::vector<Vec3d>, 2>& wands,
                       double dt) {
  auto spread = [](const std::vector<Vec3d>& p) {
    if (p.empty()) return 0.0;
    Vec3d mean = Vec3d::Zero();
    for (const Vec3d& x : p) mean += x;
    mean /= static_cast<double>(p.size());
    double sum = 0;
    for (const Vec3d& x : p) sum += (x - mean).squaredNorm();
    return sum / static_cast<double>(p.size());
  };
  const int h = spread(hands[1]) > spread(hands[0]) ? 1 : 0;
  return lag(hands[h], wands[h], dt, 0.5);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

FilmLife playFilmOnRecording(const DepthRecording& recording, const FilmEvaluationOptions& o) {
  std::unique_ptr<StabilizedWands> input = wandsOf(handsOf(recording, o), recording, o);
  const Params& params = o.run.params;
  const double h = params.frameTime;
  FilmLife life;
  life.recording = recording.name;
  life.length = input->length().value_or(0.0);
  WandFrame frame = input->at(0.0);
  Simulation sim(params, o.run.tool, frame.wands);
  life.startArea = life.peakArea = sim.stats().area;
  life.life = life.length;
  // The input's hands (the newest measured, world space) and the wands, frame by frame, for the lag.
  std::array<std::vector<Vec3d>, 2> hands, wands;
  std::array<Vec3d, 2> lastHand{frame.wands.leftPosition.cast<double>(), frame.wands.rightPosition.cast<double>()};
  const long frames = std::lround(life.length / h);
  bool burst = false;
  for (long k = 1; k <= frames; ++k) {
    const double t = static_cast<double>(k) * h;
    frame = input->at(t);
    givePerformerBody(sim, frame);
    sim.advanceFrame(frame.wands);
    const TopologyEvents& events = sim.lastEvents();
    if (events.pinchedOff && !burst) life.pinchedOff = true;
    if (events.started && !burst) {
      burst = true;
      life.life = t;
      if (!life.pinchedOff) life.burstCause = events.cause ? events.cause : "unknown";
    }
    if (!burst) life.peakArea = std::max(life.peakArea, sim.stats().area);
    life.peakWandSpeed = std::max<double>(life.peakWandSpeed,
                                          std::max(speed(frame.wands.leftVelocity), speed(frame.wands.rightVelocity)));
    const Vec3 measured[2] = {frame.leftHand, frame.rightHand};
    const Vec3 wand[2] = {frame.wands.leftPosition, frame.wands.rightPosition};
    for (int side = 0; side < 2; ++side) {
      if (measured[side].allFinite()) lastHand[side] = measured[side].cast<double>();
      hands[side].push_back(lastHand[side]);
      wands[side].push_back(wand[side].cast<double>());
    }
  }
  life.lag = lagOfMovingHand(hands, wands, h);
  return life;
}

FilmLifeSummary summarize(const std::vector<FilmLife>& lives) {
  FilmLifeSummary s;
  s.recordings = lives.size();
  if (lives.empty()) return s;
  std::vector<double> shares, growths, lags;
  size_t survived = 0;
  for (const FilmLife& l : lives) {
    survived += l.survived() ? 1 : 0;
    shares.push_back(l.lifeShare());
    growths.push_back(l.growth());
    lags.push_back(l.lag);
  }
  s.survivedShare = static_cast<double>(survived) / static_cast<double>(lives.size());
  s.medianLifeShare = median(shares);
  s.medianGrowth = median(growths);
  s.medianLag = median(lags);
  return s;
}

namespace {

// The farthest-forward point (nearest the camera) any true hand reached.
Vec3d farthestForward(const std::vector<HandSample>& truth) {
  Vec3d best = Vec3d::Constant(std::numeric_limits<double>::quiet_NaN());
  for (const HandSample& s : truth)
    for (const HandObservation* hand : {&s.left, &s.right})
      if (hand->seen() && !(hand->position.z() >= best.z())) best = hand->position;
  return best;
}

// kAwayFromHands nearer the camera than the nearest any true hand came, in front of the hands' mean: every true hand
// position lies at least that far from it, and the body behind the hands farther still.
Vec3d awayFromHands(const std::vector<HandSample>& truth) {
  Vec3d sum = Vec3d::Zero();
  double nearest = std::numeric_limits<double>::infinity();
  int seen = 0;
  for (const HandSample& s : truth)
    for (const HandObservation* hand : {&s.left, &s.right})
      if (hand->seen()) {
        sum += hand->position;
        nearest = std::min(nearest, hand->position.z());
        ++seen;
      }
  const Vec3d mean = sum / std::max(seen, 1);
  return {mean.x(), mean.y(), nearest - TouchTrial::kAwayFromHands};
}

// The recording time (s) a true hand first came within `radius` of `centre`.
std::optional<double> entryTime(const std::vector<HandSample>& truth, const Vec3d& centre, double radius) {
  for (const HandSample& s : truth)
    for (const HandObservation* hand : {&s.left, &s.right})
      if (hand->seen() && (hand->position - centre).norm() <= radius) return s.time;
  return std::nullopt;
}

}  // namespace

std::optional<TouchTrialKind> touchTrialKindOf(const std::string& recording) {
  const std::string action = recording.substr(0, recording.find('_'));
  for (const char* reach : {"a13", "a18", "a19"})
    if (action == reach) return TouchTrialKind::Reach;
  for (const char* away : {"a3", "a4", "a9", "a10"})
    if (action == away) return TouchTrialKind::Away;
  return std::nullopt;
}

bool TouchTrial::passed() const {
  if (kind == TouchTrialKind::Away) return !touchBurst.has_value();
  return touchBurst && *touchBurst >= entry - kEarliestTouch && *touchBurst <= entry + kLatestTouch;
}

TouchTrial playTouchOnRecording(const DepthRecording& recording, const FilmEvaluationOptions& o) {
  const std::optional<TouchTrialKind> kind = touchTrialKindOf(recording.name);
  if (!kind) throw HandSourceError(recording.name + ": not an action the touch is judged on (evaluate --touch)");
  if (recording.truth.empty()) throw HandSourceError(recording.name + ": no ground truth (hands.csv) to place by");
  TouchTrial trial;
  trial.recording = recording.name;
  trial.kind = *kind;
  const Vec3d centre =
      *kind == TouchTrialKind::Reach ? farthestForward(recording.truth) : awayFromHands(recording.truth);
  if (!centre.allFinite()) throw HandSourceError(recording.name + ": its ground truth never shows a hand");
  trial.bubbleAt = {centre.x(), centre.y(), centre.z()};
  FilmEvaluationOptions found = o;
  found.truthHands = false;  // the body is the depth's: the hands found in it with it
  std::unique_ptr<StabilizedWands> input = wandsOf(handsOf(recording, found), recording, found);
  RunOptions run = o.run;
  run.input.bubbleAt = trial.bubbleAt;
  run.input.bubbleRadius = TouchTrial::kBubbleRadius;
  WandFrame frame = input->at(0.0);
  // Run time 0 is the recording's frame with both hands found: the truth's times are moved to it.
  const double start = input->performerFound().value_or(0.0);
  trial.entry = entryTime(recording.truth, centre, TouchTrial::kBubbleRadius).value_or(0.0) - start;
  std::unique_ptr<Simulation> sim = startingSimulation(run, *input, frame.wands, nullptr);
  const double h = run.params.frameTime;
  const long frames = std::lround(input->length().value_or(0.0) / h);
  for (long k = 1; k <= frames; ++k) {
    const double t = static_cast<double>(k) * h;
    frame = input->at(t);
    givePerformerBody(*sim, frame);
    sim->advanceFrame(frame.wands);
    const TopologyEvents& events = sim->lastEvents();
    if (!events.started) continue;
    if (events.cause && std::string(events.cause) == "touch")
      trial.touchBurst = t;
    else
      trial.otherBurst = events.cause ? events.cause : "unknown";
    break;
  }
  return trial;
}

}  // namespace gb
