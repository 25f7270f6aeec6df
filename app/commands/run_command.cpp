#include "app/commands/run_command.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "app/commands/interrupt.h"
#include "app/commands/thread_policy.h"
#include "app/outputs/experiment_plot.h"
#include "app/outputs/osc_events.h"
#include "app/outputs/run_output.h"
#include "app/outputs/thickness_image.h"
#include "app/outputs/wand_log.h"
#include "app/show/mirror_view.h"
#include "app/show/performer_touch.h"
#include "app/show/performer_view.h"
#include "app/show/realtime_pacer.h"
#include "capture/output_file.h"
#include "capture/untrusted.h"
#include "simulation/experiments.h"
#include "simulation/simulation.h"

namespace gb {

namespace {

// A one-line progress bar on stderr: redrawn in place on a terminal, every 10% otherwise (logs stay short).
class ProgressBar {
 public:
  explicit ProgressBar(long total) : total_(total), terminal_(isatty(STDERR_FILENO) != 0) {}
  // `done` frames of the total after `wallSeconds`, the simulation at `simTime`: the frame rate and how the run
  // keeps up with the wall clock (a live show needs 1x or more).
  void update(long done, double simTime, double wallSeconds) {
    const int percent = static_cast<int>(100 * done / std::max(total_, 1L));
    if (!terminal_ && percent / 10 == lastDecile_) return;
    lastDecile_ = percent / 10;
    constexpr int width = 30;
    const int filled = width * percent / 100;
    const double wall = std::max(wallSeconds, 1e-9);
    std::fprintf(stderr, "%s[%.*s%*s] %3d%%  t = %6.2f s  %6.1f frames/s  %5.2fx real time%s", terminal_ ? "\r" : "",
                 filled, "##############################", width - filled, "", percent, simTime,
                 static_cast<double>(done) / wall, simTime / wall, terminal_ ? "" : "\n");
    std::fflush(stderr);
  }
  void finish() {
    if (terminal_) std::fputc('\n', stderr);
  }

 private:
  long total_;
  bool terminal_;
  int lastDecile_ = -1;
};

std::string meshName(long frame) {
  char name[32];
  std::snprintf(name, sizeof name, "mesh_%05ld.ply", frame);
  return name;
}

std::string imageName(long frame) {
  char name[40];
  std::snprintf(name, sizeof name, "thickness_%05ld.png", frame);
  return name;
}

void printSummary(const FrameStats& first, const FrameStats& last, long frames, int substeps, double wallSeconds,
                  const std::filesystem::path& outDir) {
  const double fps = static_cast<double>(frames) / std::max(wallSeconds, 1e-9);
  std::printf("\n%-28s %s\n", "giantbubble run", "summary");
  std::printf("%-28s %zu -> %zu\n", "particles", first.particles, last.particles);
  std::printf("%-28s %zu -> %zu\n", "triangles", first.triangles, last.triangles);
  std::printf("%-28s %.2f s (%ld frames x %d substeps)\n", "simulated", last.time, frames, substeps);
  std::printf("%-28s %.2f s (%.1f frames/s, %.0f substeps/s)\n", "wall time", wallSeconds, fps, fps * substeps);
  std::printf("%-28s %.2f (simulated s per wall s)\n", "real-time factor", last.time / std::max(wallSeconds, 1e-9));
  std::printf("%-28s %.4f -> %.4f m^2\n", "film area", first.area, last.area);
  std::printf("%-28s %.4f -> %.4f m^3\n", "swept volume", first.volume, last.volume);
  std::printf("%-28s %.3f -> %.3f um\n", "mean thickness", first.meanThickness * 1e6, last.meanThickness * 1e6);
  std::printf("%-28s %.3e J\n", "kinetic energy at the end", last.kineticEnergy);
  std::printf("%-28s %zu in flight\n", "aerosol droplets", last.droplets);
  std::printf("%-28s %s\n", "outputs", printablePath(outDir).c_str());
}

// A physics experiment's measurement next to the analytic value, printed and written to experiment.json (and its
// plot to experiment.svg).
void reportMeasurement(const RunOptions& o, const Measurement& m) {
  std::printf("\n%-28s %s\n%-28s %.6g %s\n%-28s %.6g %s (%s)\n", "measured", m.quantity.c_str(), "", m.measured,
              m.unit.c_str(), "analytic", m.analytic, m.unit.c_str(), m.law.c_str());
  if (m.analytic != 0) std::printf("%-28s %+.2f%%\n", "difference", 100.0 * m.relativeError());
  const nlohmann::json j = {{"experiment", m.experiment},
                            {"status", "finished"},
                            {"quantity", m.quantity},
                            {"unit", m.unit},
                            {"measured", m.measured},
                            {"analytic", m.analytic},
                            {"law", m.law},
                            {"relative_error", m.relativeError()}};
  writeFileAtomically(o.outDir / "experiment.json", j.dump(2) + '\n');
  std::printf("%-28s %s\n", "written to", printablePath(o.outDir / "experiment.json").c_str());
  if (!m.measuredPoints.empty()) {
    writeExperimentPlot(o.outDir / "experiment.svg", m);
    std::printf("%-28s %s\n", "plot", printablePath(o.outDir / "experiment.svg").c_str());
  }
}

// A physics experiment of the physical tension model. Ctrl-C, SIGTERM or SIGHUP stops it between frames, as it stops
// a run: experiment.json then says "interrupted" (an experiment cut short has no measurement). It says "running"
// while the experiment runs, so that one killed outright leaves no earlier "finished" behind.
int runPhysicsExperiment(const RunOptions& o) {
  const InterruptCatcher interrupts;
  writeFileAtomically(o.outDir / "experiment.json",
                      nlohmann::json{{"experiment", o.experiment}, {"status", "running"}}.dump(2) + '\n');
  const auto printLine = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  try {
    reportMeasurement(o, runExperiment(o.experiment, o.params, printLine, InterruptCatcher::requested));
    return 0;
  } catch (const ExperimentStopped& e) {
    const int signal = InterruptCatcher::signal();
    const nlohmann::json j = {{"experiment", o.experiment}, {"status", "interrupted"}};
    writeFileAtomically(o.outDir / "experiment.json", j.dump(2) + '\n');
    std::fprintf(stderr, "%s: the experiment %s %s; %s says \"interrupted\"\n", signalName(signal),
                 o.experiment.c_str(), e.what(), printablePath(o.outDir / "experiment.json").c_str());
    return 128 + signal;
  }
}

}  // namespace

namespace {

// Milliseconds since it was made or last asked.
class PhaseClock {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// Where the frame's time went, for the summary and stats.json: the simulation's phases, then the run's own work.
void addFramePhases(RunRecord& record, const FramePhases& sim, double statsMs, double outputsMs, double renderMs) {
  record.addPhase("step", sim.step);
  record.addPhase("topology", sim.topology);
  record.addPhase("contacts", sim.contacts);
  record.addPhase("stats", statsMs);
  record.addPhase("outputs", outputsMs);
  record.addPhase("render", renderMs);
}

// How long a run lasts: --duration, or a recorded input's own length (at most kMaxRunSeconds, like --duration).
double runDuration(const RunOptions& o, const WandInput& input) {
  if (!o.durationFromInput || !input.length()) return o.duration;
  const double length = std::max(*input.length(), 0.02);
  if (length <= kMaxRunSeconds) return length;
  std::fprintf(stderr, "note: the input is %.4g s long; the run stops at %.0f s (give --duration for another length)\n",
               length, kMaxRunSeconds);
  return kMaxRunSeconds;
}

// The frame whose end the poke falls on, counted, not compared as floats (0: never). A poke planned for a
// scripted gesture does not fire on a recorded or live performance unless asked for (burstOnAnyInput).
long pokeFrame(const RunOptions& o) {
  if (o.burstAt < 0 || (!o.input.scripted() && !o.burstOnAnyInput)) return 0;
  return std::max(1L, std::lround(o.burstAt / o.params.frameTime));
}

// The input's notes and warnings, on stderr (on a line of their own when the progress bar is on the terminal).
void passOnMessages(WandInput& input, bool midBar) {
  for (const std::string& m : input.takeMessages())
    std::fprintf(stderr, "%s%s\n", midBar && isatty(STDERR_FILENO) ? "\n" : "", m.c_str());
}

// What a run opens and checks before it writes anything: the hands, the film they make, OSC, the names of its outputs
// and the renderer with its environment. A run refused while opening them leaves the previous run's files in its
// folder as they were.
struct OpenedRun {
  std::unique_ptr<WandInput> input;
  double duration = 0;
  WandFrame startFrame;
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<ShowControl> show;
  std::unique_ptr<RunRenderer> renderer;
  std::unique_ptr<MirrorView> mirror;  // --view mirror: the depth camera's view with the performer drawn in
};

OpenedRun openRun(const RunOptions& o) {
  OpenedRun run;
  InputOptions input = o.input;
  input.runSeconds = o.durationFromInput ? kMaxRunSeconds : o.duration;  // a file is read no further than the run
  input.wallClock = o.realtime;
  run.mirror = std::make_unique<MirrorView>(o.render.mirror, o.render.mirrorRoom);
  const HandSourceWrapper observe = [&run](std::unique_ptr<HandSource> source) -> std::unique_ptr<HandSource> {
    auto observed = std::make_unique<ObservedHandSource>(std::move(source));
    run.mirror->attach(observed.get());
    return observed;
  };
  run.input = makeWandInput(input, o.gestureOptions, {}, o.render.mirror ? observe : HandSourceWrapper());
  if (o.render.enabled && o.render.mirror && !run.input->cameraCalibration())
    std::fprintf(stderr,
                 "note: --view mirror needs a depth camera input (kinect, fakenect:DIR): the virtual stage "
                 "is drawn instead\n");
  std::printf("input: %s\n", run.input->describe().c_str());
  run.duration = runDuration(o, *run.input);
  run.startFrame = run.input->at(0.0);
  passOnMessages(*run.input, false);
  std::string backendReport;
  std::unique_ptr<Stepper> stepper = makeStepper(o.backend, o.device, backendReport, o.betweenSteps);
  std::printf("%s\n", backendReport.c_str());
  run.sim = startingSimulation(o, *run.input, run.startFrame.wands, std::move(stepper));
  if (const std::string bubble = bubbleInWords(o, *run.sim); !bubble.empty()) std::printf("film: %s\n", bubble.c_str());
  run.show = std::make_unique<ShowControl>(o.osc);
  if (o.render.enabled) {
    try {
      run.renderer = std::make_unique<RunRenderer>(o.render, o.outDir, *run.sim, o.device);
    } catch (const OutputError&) {  // the video's name: another process writing it, say; not the device
      throw;
    } catch (const std::exception& e) {
      if (!o.renderIfPossible) throw;
      std::fprintf(stderr, "note: no rendered frames (%s); the thickness images are still written\n", e.what());
    }
  }
  return run;
}

// Simulates the frames of an opened run and writes every output; returns the exit code (run_command.h).
int runFrames(const RunOptions& o, OpenedRun& run, RunRecord& record) {
  WandInput& input = *run.input;
  Simulation& sim = *run.sim;
  ShowControl& show = *run.show;
  RunRenderer* renderer = run.renderer.get();
  WandLog wandLog(o.outDir / "wands.csv");
  wandLog.add(0.0, run.startFrame);
  const long frames = std::max(1L, std::lround(run.duration / o.params.frameTime));
  const long poke = pokeFrame(o);
  if (o.burstAt >= 0 && poke == 0)
    std::printf("note: no poke at %.2f s: the input is not a script (--burst-at pokes any input)\n", o.burstAt);
  std::printf("giantbubble run: %zu particles, %zu triangles, %d substeps of %.3g ms per %.3g s frame, %ld frames\n",
              sim.particleCount(), sim.triangleCount(), sim.substepsPerFrame(),
              1e3 * o.params.frameTime / sim.substepsPerFrame(), o.params.frameTime, frames);

  SimulationThreads threads;  // one fewer for each core another process keeps busy (thread_policy.h)
  StatsWriter stats(o.outDir / "stats.csv");
  const FrameStats first = sim.stats();
  // A performer waited for: the film is made when both hands are found, and the run's time 0 is then.
  const std::string created =
      input.performerFound().value_or(0.0) > 0.0 ? "performer_found film_created" : "film_created";
  stats.write(0, first, sim.substepsPerFrame(), 0.0, created);
  record.start(first);
  if (const auto found = input.performerFound()) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.3f", *found);
    record.note("performer_found_after_s", seconds);
  }
  show.frame(sim, first, created);
  if (o.plyEvery > 0) writePly(o.outDir / meshName(0), sim.film());
  ImageFraming framing;  // the images frame the film wherever it goes, growing only (no jitter)
  if (o.imageEvery > 0)
    writeThicknessImage(o.outDir / imageName(0), sim.film(), sim.aerosol(), framing.frame(sim.film()));
  if (renderer)
    renderer->frame(0, sim, run.startFrame.wands,
                    [&](RenderFrame& f) { run.mirror->apply(f, input.cameraCalibration()); });

  const InterruptCatcher interrupts;  // Ctrl-C or SIGTERM: the frame in flight finishes, then the outputs
  ProgressBar bar(frames);
  FrameStats last = first;
  std::string status = "finished";
  int exitCode = 0;
  long done = 0;
  StepRenderOverlap overlap;
  const auto runStart = std::chrono::steady_clock::now();
  // With --realtime the image is drawn smaller while the machine is behind, then the sweeps go down (RealTimePacer).
  const double smallestImage = o.realtime && renderer ? kRealtimeRunSmallestImage : 1.0;
  RealTimePacer pacer({o.params.frameTime, sim.solverSweeps(), 3, 1, smallestImage}, runStart);
  for (long frame = 1; frame <= frames; ++frame) {
    if (const int signal = InterruptCatcher::signal()) {
      status = "interrupted";
      exitCode = 128 + signal;
      bar.finish();
      std::fprintf(stderr, "%s: stopping after frame %ld of %ld; writing the outputs\n", signalName(signal), done,
                   frames);
      break;
    }
    const double t = static_cast<double>(frame) * o.params.frameTime;
    if (o.realtime) {  // the frame is shown when the wall clock reaches it: wait when ahead
      std::this_thread::sleep_until(runStart + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                   std::chrono::duration<double>(t - o.params.frameTime)));
      sim.setSolverSweeps(pacer.sweeps());
    }
    const WandFrame wands = input.at(t);  // a live camera may wait here for its next frame
    passOnMessages(input, o.progress);
    const auto frameStart = std::chrono::steady_clock::now();
    std::string events;
    if (frame == poke && pokeTop(sim)) events += "poked ";  // nothing to poke once the film is gone
    threads.update();
    try {
      givePerformerBody(sim, wands);
      sim.advanceFrame(wands.wands);
      overlap.addStep(sim.stepper(), steadySeconds(frameStart), steadySeconds(std::chrono::steady_clock::now()));
    } catch (const SimulationUnstable& e) {
      bar.finish();
      std::fprintf(stderr, "error: %s\nstopped at frame %ld of %ld; outputs up to frame %ld are in %s\n", e.what(),
                   frame, frames, frame - 1, printablePath(o.outDir).c_str());
      if (o.plyEvery > 0) writePly(o.outDir / ("unstable_" + meshName(frame)), sim.film());
      status = "unstable at frame " + std::to_string(frame) + ": " + e.what();
      exitCode = 3;
      break;
    }
    wandLog.add(t, wands);  // a row beside each row of stats.csv: none for a frame that blew up
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count();
    PhaseClock phase;
    last = sim.stats();
    events += describeEvents(sim.lastEvents());
    if (!events.empty() && events.back() == ' ') events.pop_back();
    const std::string touched = touchInWords(sim, events);
    const std::optional<Touch> touch = touched.empty() ? std::nullopt : sim.lastTouch();
    if (touch) {
      std::printf("%s%.2f s: %s\n", o.progress && isatty(STDOUT_FILENO) ? "\n" : "", last.time, touched.c_str());
      record.addTouch(last.time, *touch);
    }
    stats.write(frame, last, sim.substepsPerFrame(), ms, events, touch);
    record.addFrame(last, sim.substepsPerFrame(), ms, events);
    show.frame(sim, last, events);
    const double statsMs = phase.lap();
    if (o.imageEvery > 0 && frame % o.imageEvery == 0)
      writeThicknessImage(o.outDir / imageName(frame), sim.film(), sim.aerosol(), framing.frame(sim.film()));
    if (o.plyEvery > 0 && frame % o.plyEvery == 0) {
      writePly(o.outDir / meshName(frame), sim.film());
      if (sim.aerosol().size() > 0) writeAerosolPly(o.outDir / ("aerosol" + meshName(frame).substr(4)), sim.aerosol());
    }
    const double outputsMs = phase.lap();
    if (renderer)
      renderer->frame(frame, sim, wands.wands,
                      [&](RenderFrame& f) { run.mirror->apply(f, input.cameraCalibration()); });
    if (renderer) overlap.addRender(renderer->takeDrawnIntervals());
    const double renderMs = renderer ? phase.lap() : 0.0;
    addFramePhases(record, sim.lastPhases(), statsMs, outputsMs, renderMs);
    pacer.record(1, ms + statsMs + outputsMs, renderMs);
    if (o.realtime && renderer) renderer->setDynamicScale(pacer.renderScale());
    done = frame;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - runStart).count();
    if (o.progress) bar.update(frame, sim.time(), wall);
  }
  if (exitCode == 0) bar.finish();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - runStart).count();
  // The outputs, whatever stopped the run: the video first (a failed encoder is noted, not thrown), then the
  // row files closed and checked, then the summary.
  if (renderer) {
    renderer->finish();
    overlap.addRender(renderer->takeDrawnIntervals());
    record.setOverlap(overlap.totals(), wall);
    if (!renderer->videoError().empty()) {
      record.note("video_error", renderer->videoError());
      if (exitCode == 0) exitCode = 5;
    }
  }
  stats.close();
  wandLog.close();
  wandLog.writePlot(o.outDir / "wands.svg",
                    "giantbubble run" + (status == "finished" ? "" : " (" + status.substr(0, status.find(':')) + ")") +
                        ": " + input.describe(),
                    input.camera());
  record.setRealTimeFactor(last.time / std::max(wall, 1e-9));
  record.setEnergyBudget(sim.energyBudgetRecord());
  record.setReadback(sim.readbackRecord());
  record.writeJson(o.outDir / "stats.json", o.scene, status);
  if (status == "interrupted") {
    std::fprintf(stderr,
                 "interrupted: %ld of %ld frames simulated; outputs in %s (stats.json status \"interrupted\")\n", done,
                 frames, printablePath(o.outDir).c_str());
    return exitCode;
  }
  if (exitCode == 3) return exitCode;
  printSummary(first, last, frames, sim.substepsPerFrame(), wall, o.outDir);
  std::fputs(record.story().c_str(), stdout);
  record.printPhases();
  record.printOverlap();
  record.printTable1(o.scene);
  return exitCode;
}

// What a run writes, checked together before anything is (output_file.h): its folder, the files it writes into it
// every time and the video.
std::vector<Output> outputsOf(const RunOptions& o) {
  std::vector<Output> outputs = {{"--out", o.outDir, Output::Kind::Folder, "", true}};
  const bool experiment = !o.experiment.empty();
  for (const char* name : experiment ? std::vector<const char*>{"experiment.json", "experiment.svg"}
                                     : std::vector<const char*>{"stats.json", "stats.csv", "wands.csv", "wands.svg"})
    outputs.push_back({"", o.outDir / name, Output::Kind::File, "", true});
  if (!experiment && o.render.enabled && !o.render.video.empty())
    outputs.push_back({"--video", o.outDir / o.render.video, Output::Kind::File, ".mp4", true});
  return outputs;
}

}  // namespace

int runSimulation(const RunOptions& o) {
  // A second run into the same folder is refused while this one lives.
  const std::vector<OutputFolder> holds = checkOutputs(outputsOf(o));
  if (!o.experiment.empty()) return runPhysicsExperiment(o);
  OpenedRun run = openRun(o);
  // From here the folder is this run's: stats.json says so first, so that a run that dies before it ends leaves no
  // earlier "finished" beside rows of its own.
  markRunning(o.outDir / "stats.json", o.scene);
  RunRecord record;
  try {
    return runFrames(o, run, record);
  } catch (const std::exception& e) {
    try {
      record.writeJson(o.outDir / "stats.json", o.scene, std::string("failed: ") + e.what());
    } catch (const OutputError&) {  // the disk that stopped the run: stats.json still says "running"
    }
    throw;
  }
}

}  // namespace gb
