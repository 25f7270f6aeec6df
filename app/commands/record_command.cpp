#include "app/commands/record_command.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>

#include "app/commands/cli_checks.h"
#include "app/commands/interrupt.h"
#include "capture/depth_plot.h"
#include "capture/output_file.h"
#include "capture/trajectory_file.h"
#include "capture/trajectory_metrics.h"
#include "capture/trajectory_plot.h"
#include "capture/untrusted.h"

namespace gb {

namespace {

// The recorded input run through one stabilizer, the way `giantbubble run` would, sampled at the input's own
// times: in world space for the plot (input hands not measured are NaN there), in camera space, the hand's
// own metres, for the metrics (input hands held where not measured).
struct Stabilized {
  std::vector<Vec3> plotInput[2], wand[2];
  std::vector<Vec3d> input[2], cameraWand[2], truth[2];
  Vec3 camera;  // world space
};

Stabilized stabilize(const std::vector<HandSample>& samples, StabilizerKind kind, const InputOptions& options,
                     const ScriptedHandSource* script) {
  StabilizerOptions stabilizer = stabilizerOptionsOf(options);
  stabilizer.kind = kind;
  StabilizedWands wands(std::make_unique<ReplayHandSource>(samples, "recorded input"), stabilizer,
                        calibrationOf(options));
  const Calibration& c = wands.calibration();
  Stabilized out;
  out.camera = c.toWorld(Vec3d::Zero()).cast<float>();
  for (const HandSample& s : samples) {
    const WandFrame f = wands.at(s.time - samples.front().time);
    const HandSample truth = script ? script->truth(s.time) : HandSample{};
    for (int h = 0; h < 2; ++h) {
      const Hand hand = h == 0 ? Hand::Left : Hand::Right;
      const HandObservation& o = s.hand(hand);
      out.plotInput[h].push_back(o.measured ? Vec3(c.toWorld(o.position).cast<float>()) : Vec3(Vec3::Constant(NAN)));
      if (o.seen()) out.input[h].push_back(o.position);
      const Vec3 wand = h == 0 ? f.wands.leftPosition : f.wands.rightPosition;
      out.wand[h].push_back(wand);
      out.cameraWand[h].push_back(c.toCamera(wand.cast<double>()));
      if (script) out.truth[h].push_back(truth.hand(hand).position);
    }
  }
  return out;
}

double bothHands(const std::function<double(int)>& perHand) {
  return std::sqrt(0.5 * (perHand(0) * perHand(0) + perHand(1) * perHand(1)));
}

// How many times the stabilizer reduced the jitter: "-" when there was none to reduce (hands held still).
std::string reduction(double in, double out) {
  if (!(in > 0.0 && out > 0.0)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.1fx", in / out);
  return text;
}

void printReport(const std::vector<HandSample>& samples, const InputOptions& options,
                 const ScriptedHandSource* script) {
  const double dt = (samples.back().time - samples.front().time) / static_cast<double>(samples.size() - 1);
  std::printf(
      "\njitter (RMS second difference) and lag of the wands, in camera space (the hands' own metres), "
      "%zu samples at %.1f per second\n",
      samples.size(), 1.0 / dt);
  std::printf("%-10s %12s %12s %10s %14s", "stabilizer", "input (mm)", "wand (mm)", "reduction", "lag/input (ms)");
  if (script) std::printf(" %14s %15s", "lag/truth (ms)", "RMS error (mm)");
  std::printf("\n");
  for (const auto& [name, kind] :
       {std::pair{"bspline", StabilizerKind::BSpline}, {"one-euro", StabilizerKind::OneEuro}}) {
    const Stabilized s = stabilize(samples, kind, options, script);
    if (s.input[0].size() != samples.size() || s.input[1].size() != samples.size()) {
      std::printf("%-10s (a hand is missing from the first samples: no report)\n", name);
      continue;
    }
    const double in = bothHands([&](int h) { return jitter(s.input[h]); });
    const double out = bothHands([&](int h) { return jitter(s.cameraWand[h]); });
    const double lagInput =
        0.5 * (lag(s.input[0], s.cameraWand[0], dt, 0.5) + lag(s.input[1], s.cameraWand[1], dt, 0.5));
    std::printf("%-10s %12.2f %12.2f %10s %14.0f", name, 1e3 * in, 1e3 * out, reduction(in, out).c_str(),
                1e3 * lagInput);
    if (script) {
      double error[2] = {0, 0};
      const double lagTruth = 0.5 * (lag(s.truth[0], s.cameraWand[0], dt, 0.5, &error[0]) +
                                     lag(s.truth[1], s.cameraWand[1], dt, 0.5, &error[1]));
      std::printf(" %14.0f %15.1f", 1e3 * lagTruth, 1e3 * bothHands([&](int h) { return error[h]; }));
    }
    std::printf("\n");
  }
}

// What a recording writes, checked together before it starts (output_file.h).
std::vector<Output> outputsOf(const RecordOptions& o) {
  std::vector<Output> outputs;
  if (!o.trajectory.empty()) outputs.push_back({"--trajectory", o.trajectory, Output::Kind::File, ".csv"});
  if (!o.plot.empty()) outputs.push_back({"--plot", o.plot, Output::Kind::File, ".svg"});
  if (!o.depthPlot.empty()) outputs.push_back({"--depth-plot", o.depthPlot, Output::Kind::File, ".png"});
  if (!o.fakenect.empty()) outputs.push_back({"--fakenect", o.fakenect, Output::Kind::NewFolder, "", true});
  return outputs;
}

}  // namespace

CLI::App* addRecordCommand(CLI::App& app, RecordOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "record", "read a hand input and keep it: a fakenect recording of the depth, a trajectory CSV, a plot, a report");
  addInputOptions(cmd, o.input);
  cmd->add_option("--trajectory", o.trajectory, "write the hands as a trajectory CSV (camera space), FILE.csv")
      ->check(NotEmpty());
  cmd->add_option("--fakenect", o.fakenect,
                  "write the depth frames as a fakenect recording into this new folder "
                  "(input kinect or fakenect:DIR)")
      ->check(NotEmpty());
  cmd->add_option("--plot", o.plot, "write the input hands against the stabilized wands as SVG, FILE.svg")
      ->check(NotEmpty());
  cmd->add_option("--depth-plot", o.depthPlot,
                  "write one depth frame with the hands found in it as PNG, FILE.png (input kinect or fakenect:DIR): "
                  "the view to set the camera up by")
      ->check(NotEmpty());
  cmd->add_option("--depth-plot-frame", o.depthPlotFrame, "the frame --depth-plot draws, from 0 (default: the last)")
      ->transform(WholeNumber(0, 100000000));
  cmd->add_flag("--report", o.report, "print the jitter and lag of both stabilizers on this input");
  cmd->add_option("--duration", o.duration,
                  "seconds to record (default: all of a recorded input, a script's "
                  "stroke, a live camera until Ctrl-C)")
      ->check(FiniteRange(0.0, 86400.0));
  cmd->add_option("--speed", o.gesture.speed, "peak wand speed of a scripted input (m/s)")
      ->check(FiniteRange(0.0, 20.0));
  cmd->add_option("--noise", o.noise.sigma, "Gaussian noise (m, per coordinate) added to a scripted input")
      ->check(FiniteRange(0.0, 1.0));
  cmd->add_option("--outliers", o.noise.outlierRate, "fraction of a scripted input's samples made outliers")
      ->check(FiniteRange(0.0, 1.0));
  cmd->add_option("--outlier-distance", o.noise.outlierDistance, "how far an outlier lands (m)")
      ->check(FiniteRange(0.0, 5.0));
  cmd->add_option("--seed", o.noise.seed, "random seed of the noise")->transform(WholeNumber(0, 4294967295.0));
  return cmd;
}

namespace {

// What a recording read: the hands, and for --depth-plot the depth frame asked for with what the detection saw.
struct Recording {
  std::vector<HandSample> samples;
  int depthFrames = 0;
  bool plotNext = false;  // the depth frame just read is the one to plot
  kinect::DepthFrame plotted;
  Detection plottedDetection;
  HandSample plottedHands;
};

// Once a second of a live recording: the hands seen, which body is taken and why, and what to change, so that a
// performer can set up by it.
void printLiveProgress(const Recording& r, const HandSample& s, double elapsed, const DepthHandSource* depth) {
  const std::string why =
      depth ? depth->detection().why + (depth->detection().advice.empty() ? "" : "; " + depth->detection().advice) : "";
  std::fprintf(stderr, "%.0f s, %zu frames, left hand %s, right hand %s: %s\n", elapsed, r.samples.size(),
               s.left.measured ? "seen" : "not seen", s.right.measured ? "seen" : "not seen", why.c_str());
}

// Reads `source` until it ends, `duration` s have been read (negative: no limit) or Ctrl-C, writing each sample
// to `trajectory` as it comes (and, through the depth callback, each depth frame to the fakenect recording).
void readSamples(HandSource& source, DepthHandSource* depth, TrajectoryWriter* trajectory, double duration, bool live,
                 Recording& r) {
  double lastProgress = -1.0;
  try {
    while (!InterruptCatcher::requested()) {
      std::optional<HandSample> s = source.next();
      for (const std::string& m : source.takeMessages()) std::fprintf(stderr, "%s\n", m.c_str());
      if (!s) break;
      if (!r.samples.empty() && duration >= 0 && s->time - r.samples.front().time > duration + 1e-9) break;
      r.samples.push_back(*s);
      if (trajectory) trajectory->write(*s);
      if (depth && r.plotNext) {
        r.plottedDetection = depth->detection();  // as the performance saw it: the room and the hands so far
        r.plottedHands = *s;
        r.plotNext = false;
      }
      const double elapsed = s->time - r.samples.front().time;
      if (live && elapsed - lastProgress >= 1.0) {
        lastProgress = elapsed;
        printLiveProgress(r, *s, elapsed, depth);
      }
    }
  } catch (const HandSourceLost& e) {
    std::fprintf(stderr, "warning: input lost after %zu samples: %s; what was recorded is kept\n", r.samples.size(),
                 e.what());
  }
}

// --plot: the recorded hands and the wands the stabilizer makes of them.
void writePlotOf(const RecordOptions& o, const std::vector<HandSample>& samples, const HandSource& source,
                 const ScriptedHandSource* script) {
  const Stabilized s = stabilize(samples, stabilizerFromName(o.input.stabilizer), o.input, script);
  TrajectoryPlot plot;
  plot.title = source.describe() + ", " + o.input.stabilizer + " stabilizer";
  plot.leftInput = s.plotInput[0];
  plot.rightInput = s.plotInput[1];
  plot.leftWand = s.wand[0];
  plot.rightWand = s.wand[1];
  plot.camera = s.camera;
  writeTrajectoryPlot(o.plot, plot);
  std::printf("plot written to %s\n", printablePath(o.plot).c_str());
}

// --depth-plot: the depth frame asked for, the body taken and the hands reported. False when there was no such frame.
bool writeDepthPlotOf(const RecordOptions& o, const Recording& r) {
  if (o.depthPlotFrame >= r.depthFrames) {
    std::fprintf(stderr, "error: --depth-plot-frame %d: the input had %d depth frames\n", o.depthPlotFrame,
                 r.depthFrames);
    return false;
  }
  writeDepthPlot(o.depthPlot, r.plotted, r.plottedDetection, r.plottedHands);
  std::printf("depth plot written to %s: %s; hands reported: %s%s\n", printablePath(o.depthPlot).c_str(),
              r.plottedDetection.why.c_str(), r.plottedHands.left.measured ? "left " : "",
              r.plottedHands.right.measured ? "right" : (r.plottedHands.left.measured ? "" : "none"));
  if (!r.plottedDetection.advice.empty()) std::printf("advice: %s\n", r.plottedDetection.advice.c_str());
  return true;
}

}  // namespace

int runRecord(const RecordOptions& o) {
  if (o.trajectory.empty() && o.fakenect.empty() && o.plot.empty() && o.depthPlot.empty() && !o.report) {
    std::fprintf(stderr,
                 "error: nothing to record: give --trajectory FILE, --fakenect DIR, --plot FILE, --depth-plot FILE or "
                 "--report\n");
    return 1;
  }
  const std::vector<OutputFolder> holds = checkOutputs(outputsOf(o));  // refused now, not after the recording
  const bool noisy = o.noise.sigma > 0 || o.noise.outlierRate > 0;
  if (noisy && !o.input.scripted()) {
    std::fprintf(stderr, "error: --noise and --outliers apply to a scripted input (script:NAME) only\n");
    return 1;
  }
  SourceOptions sourceOptions = sourceOptionsOf(o.input, o.gesture);
  sourceOptions.noise = o.noise;
  std::unique_ptr<HandSource> source = makeHandSource(o.input.spec(), sourceOptions);
  const auto* script = dynamic_cast<const ScriptedHandSource*>(source.get());
  auto* depth = dynamic_cast<DepthHandSource*>(source.get());
  std::printf("recording from %s\n", source->describe().c_str());
  if ((!o.fakenect.empty() || !o.depthPlot.empty()) && !depth) {
    std::fprintf(stderr,
                 "error: --fakenect and --depth-plot need depth frames: the input must be kinect or fakenect:DIR\n");
    return 1;
  }

  std::unique_ptr<FakenectWriter> fakenect;
  if (!o.fakenect.empty()) fakenect = std::make_unique<FakenectWriter>(o.fakenect);
  Recording recording;
  const double base = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  if (depth)
    depth->onFrame([&, base](const kinect::DepthFrame& f) {
      if (fakenect) fakenect->write(f, base + f.time);
      recording.plotNext = o.depthPlotFrame < 0 || recording.depthFrames == o.depthPlotFrame;
      if (recording.plotNext) recording.plotted = f;
      ++recording.depthFrames;
    });
  std::unique_ptr<TrajectoryWriter> trajectory;
  if (!o.trajectory.empty()) trajectory = std::make_unique<TrajectoryWriter>(o.trajectory);

  double duration = o.duration;
  if (duration < 0 && script) duration = o.gesture.start + o.gesture.duration + 0.5;
  const bool live = depth && !source->length();
  if (live && duration < 0) std::printf("recording until Ctrl-C\n");
  std::optional<InterruptCatcher> interrupts(std::in_place);  // Ctrl-C ends the recording, keeping it
  readSamples(*source, depth, trajectory.get(), duration, live, recording);
  const int exitStatus = InterruptCatcher::exitStatus(0);  // docs/user-guide.md: 130 after Ctrl-C, 143 after SIGTERM
  if (InterruptCatcher::requested())
    std::fprintf(stderr, "%s: the recording stops; what was recorded is written\n",
                 signalName(InterruptCatcher::signal()));
  interrupts.reset();

  const std::vector<HandSample>& samples = recording.samples;
  if (samples.empty()) {
    std::fprintf(stderr, "error: no samples from %s\n", source->describe().c_str());
    return 1;
  }
  std::printf("%zu samples, %.2f s\n", samples.size(), samples.back().time - samples.front().time);
  if (trajectory) {
    trajectory->close();
    std::printf("trajectory written to %s\n", printablePath(o.trajectory).c_str());
  }
  if (fakenect)
    std::printf("fakenect recording written to %s (%d depth frames)\n", printablePath(o.fakenect).c_str(),
                fakenect->frames());
  if (!o.plot.empty()) writePlotOf(o, samples, *source, script);
  if (!o.depthPlot.empty() && !writeDepthPlotOf(o, recording)) return 1;
  if (o.report) {
    if (samples.size() < 10) {
      std::fprintf(stderr, "error: too few samples for a report\n");
      return 1;
    }
    printReport(samples, o.input, script);
  }
  return exitStatus;
}

}  // namespace gb
