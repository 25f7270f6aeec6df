#include "film_evaluation.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "input_options.h"
#include "performer_touch.h"
#include "simulation.h"
#include "trajectory_metrics.h"

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

}  // namespace gb
