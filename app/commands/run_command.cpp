#include "app/commands/run_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "app/commands/cli_checks.h"
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

// The frames of an opened run, simulated one after another, and every output they write. A run ends finished,
// interrupted (Ctrl-C or SIGTERM: the frame in flight finishes, then the outputs) or unstable (the outputs up to
// the frame before).
class FrameLoop {
 public:
  FrameLoop(const RunOptions& o, OpenedRun& run, RunRecord& record)
      : o_(o),
        run_(run),
        input_(*run.input),
        sim_(*run.sim),
        renderer_(run.renderer.get()),
        record_(record),
        wandLog_(o.outDir / "wands.csv"),
        stats_(o.outDir / "stats.csv"),
        frames_(std::max(1L, std::lround(run.duration / o.params.frameTime))),
        poke_(pokeFrame(o)) {}

  long frames() const { return frames_; }

  // Frame 0: the film as the hands made it, in every output.
  void writeStart() {
    wandLog_.add(0.0, run_.startFrame);
    if (o_.burstAt >= 0 && poke_ == 0)
      std::printf("note: no poke at %.2f s: the input is not a script (--burst-at pokes any input)\n", o_.burstAt);
    std::printf("giantbubble run: %zu particles, %zu triangles, %d substeps of %.3g ms per %.3g s frame, %ld frames\n",
                sim_.particleCount(), sim_.triangleCount(), sim_.substepsPerFrame(),
                1e3 * o_.params.frameTime / sim_.substepsPerFrame(), o_.params.frameTime, frames_);
    first_ = last_ = sim_.stats();
    // A performer waited for: the film is made when both hands are found, and the run's time 0 is then.
    const std::string created =
        input_.performerFound().value_or(0.0) > 0.0 ? "performer_found film_created" : "film_created";
    stats_.write(0, first_, sim_.substepsPerFrame(), 0.0, created);
    record_.start(first_);
    if (const auto found = input_.performerFound()) {
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%.3f", *found);
      record_.note("performer_found_after_s", seconds);
    }
    run_.show->frame(sim_, first_, created);
    writeFiles(0);
    render(0, run_.startFrame.wands);
  }

  // Starts the wall clock the run is measured (and, with --realtime, paced) by.
  void startClock() {
    runStart_ = std::chrono::steady_clock::now();
    // With --realtime the image is drawn smaller while the machine is behind, then the sweeps go down.
    const double smallestImage = o_.realtime && renderer_ ? kRealtimeRunSmallestImage : 1.0;
    pacer_.emplace(PacerOptions{o_.params.frameTime, sim_.solverSweeps(), 3, 1, smallestImage}, runStart_);
  }

  // Simulates frame `frame` and writes its outputs; false when the run stops before it (a signal, an instability).
  bool advance(long frame) {
    if (const int signal = InterruptCatcher::signal()) {
      stopOnSignal(signal);
      return false;
    }
    const double t = static_cast<double>(frame) * o_.params.frameTime;
    if (o_.realtime) waitForWallClock(t);
    const WandFrame wands = input_.at(t);  // a live camera may wait here for its next frame
    passOnMessages(input_, o_.progress);
    const auto frameStart = std::chrono::steady_clock::now();
    std::string events;
    if (frame == poke_ && pokeTop(sim_)) events += "poked ";  // nothing to poke once the film is gone
    threads_.update();
    try {
      givePerformerBody(sim_, wands);
      sim_.advanceFrame(wands.wands);
      overlap_.addStep(sim_.stepper(), steadySeconds(frameStart), steadySeconds(std::chrono::steady_clock::now()));
    } catch (const SimulationUnstable& e) {
      stopUnstable(frame, e);
      return false;
    }
    wandLog_.add(t, wands);  // a row beside each row of stats.csv: none for a frame that blew up
    const double stepMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count();
    writeFrame(frame, wands, events, stepMs);
    done_ = frame;
    if (o_.progress) bar_.update(frame, sim_.time(), wallSeconds());
    return true;
  }

  // The outputs, whatever stopped the run: the video first (a failed encoder is noted, not thrown), then the row
  // files closed and checked, then the summary. Returns the exit code (run_command.h).
  int finish() {
    if (exitCode_ == 0) bar_.finish();
    const double wall = wallSeconds();
    if (renderer_) finishVideo(wall);
    stats_.close();
    wandLog_.close();
    wandLog_.writePlot(o_.outDir / "wands.svg",
                       "giantbubble run" +
                           (status_ == "finished" ? "" : " (" + status_.substr(0, status_.find(':')) + ")") + ": " +
                           input_.describe(),
                       input_.camera());
    record_.setRealTimeFactor(last_.time / std::max(wall, 1e-9));
    record_.setEnergyBudget(sim_.energyBudgetRecord());
    record_.setReadback(sim_.readbackRecord());
    record_.writeJson(o_.outDir / "stats.json", o_.scene, status_);
    if (status_ == "interrupted") {
      std::fprintf(stderr,
                   "interrupted: %ld of %ld frames simulated; outputs in %s (stats.json status \"interrupted\")\n",
                   done_, frames_, printablePath(o_.outDir).c_str());
      return exitCode_;
    }
    if (exitCode_ == 3) return exitCode_;
    printSummary(first_, last_, frames_, sim_.substepsPerFrame(), wall, o_.outDir);
    std::fputs(record_.story().c_str(), stdout);
    record_.printPhases();
    record_.printOverlap();
    record_.printTable1(o_.scene);
    return exitCode_;
  }

 private:
  double wallSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - runStart_).count();
  }

  // With --realtime the frame is shown when the wall clock reaches it: wait when ahead.
  void waitForWallClock(double t) {
    std::this_thread::sleep_until(runStart_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                  std::chrono::duration<double>(t - o_.params.frameTime)));
    sim_.setSolverSweeps(pacer_->sweeps());
  }

  void stopOnSignal(int signal) {
    status_ = "interrupted";
    exitCode_ = 128 + signal;
    bar_.finish();
    std::fprintf(stderr, "%s: stopping after frame %ld of %ld; writing the outputs\n", signalName(signal), done_,
                 frames_);
  }

  void stopUnstable(long frame, const SimulationUnstable& e) {
    bar_.finish();
    std::fprintf(stderr, "error: %s\nstopped at frame %ld of %ld; outputs up to frame %ld are in %s\n", e.what(), frame,
                 frames_, frame - 1, printablePath(o_.outDir).c_str());
    if (o_.plyEvery > 0) writePly(o_.outDir / ("unstable_" + meshName(frame)), sim_.film());
    status_ = "unstable at frame " + std::to_string(frame) + ": " + e.what();
    exitCode_ = 3;
  }

  // A simulated frame's rows, touches, files and picture, and where its time went.
  void writeFrame(long frame, const WandFrame& wands, std::string events, double stepMs) {
    PhaseClock phase;
    last_ = sim_.stats();
    events += describeEvents(sim_.lastEvents());
    if (!events.empty() && events.back() == ' ') events.pop_back();
    const std::string touched = touchInWords(sim_, events);
    const std::optional<Touch> touch = touched.empty() ? std::nullopt : sim_.lastTouch();
    if (touch) {
      std::printf("%s%.2f s: %s\n", o_.progress && isatty(STDOUT_FILENO) ? "\n" : "", last_.time, touched.c_str());
      record_.addTouch(last_.time, *touch);
    }
    stats_.write(frame, last_, sim_.substepsPerFrame(), stepMs, events, touch);
    record_.addFrame(last_, sim_.substepsPerFrame(), stepMs, events);
    run_.show->frame(sim_, last_, events);
    const double statsMs = phase.lap();
    writeFiles(frame);
    const double outputsMs = phase.lap();
    render(frame, wands.wands);
    const double renderMs = renderer_ ? phase.lap() : 0.0;
    addFramePhases(record_, sim_.lastPhases(), statsMs, outputsMs, renderMs);
    pacer_->record(1, stepMs + statsMs + outputsMs, renderMs);
    if (o_.realtime && renderer_) renderer_->setDynamicScale(pacer_->renderScale());
  }

  // The thickness image and the PLY meshes due at `frame`.
  void writeFiles(long frame) {
    if (o_.imageEvery > 0 && frame % o_.imageEvery == 0)
      writeThicknessImage(o_.outDir / imageName(frame), sim_.film(), sim_.aerosol(), imageFraming_.frame(sim_.film()));
    if (o_.plyEvery > 0 && frame % o_.plyEvery == 0) {
      writePly(o_.outDir / meshName(frame), sim_.film());
      if (frame > 0 && sim_.aerosol().size() > 0)
        writeAerosolPly(o_.outDir / ("aerosol" + meshName(frame).substr(4)), sim_.aerosol());
    }
  }

  void render(long frame, const WandState& wands) {
    if (!renderer_) return;
    renderer_->frame(frame, sim_, wands, [&](RenderFrame& f) { run_.mirror->apply(f, input_.cameraCalibration()); });
    overlap_.addRender(renderer_->takeDrawnIntervals());
  }

  void finishVideo(double wall) {
    renderer_->finish();
    overlap_.addRender(renderer_->takeDrawnIntervals());
    record_.setOverlap(overlap_.totals(), wall);
    if (!renderer_->videoError().empty()) {
      record_.note("video_error", renderer_->videoError());
      if (exitCode_ == 0) exitCode_ = 5;
    }
  }

  const RunOptions& o_;
  OpenedRun& run_;
  WandInput& input_;
  Simulation& sim_;
  RunRenderer* renderer_;
  RunRecord& record_;
  WandLog wandLog_;
  StatsWriter stats_;
  const long frames_;
  const long poke_;
  SimulationThreads threads_;  // one fewer for each core another process keeps busy (thread_policy.h)
  ImageFraming imageFraming_;  // the images frame the film wherever it goes, growing only (no jitter)
  ProgressBar bar_{frames_};
  StepRenderOverlap overlap_;
  std::chrono::steady_clock::time_point runStart_ = std::chrono::steady_clock::now();
  std::optional<RealTimePacer> pacer_;
  FrameStats first_, last_;
  std::string status_ = "finished";
  int exitCode_ = 0;
  long done_ = 0;
};

// Simulates the frames of an opened run and writes every output; returns the exit code (run_command.h).
int runFrames(const RunOptions& o, OpenedRun& run, RunRecord& record) {
  FrameLoop loop(o, run, record);
  loop.writeStart();
  const InterruptCatcher interrupts;  // from here a signal stops the run between frames
  loop.startClock();
  for (long frame = 1; frame <= loop.frames(); ++frame)
    if (!loop.advance(frame)) break;
  return loop.finish();
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

CLI::App* addRunCommand(CLI::App& app, RunCommandLine& line) {
  RunOptions& run = line.options;
  CLI::App* command = app.add_subcommand("run", "simulate a performance headless and write its outputs");
  command
      ->add_option("--scene", line.scene,
                   "a built-in scene (giantbubble scenes lists them) or a scene file (.toml); "
                   "the other options change it")
      ->check(NotEmpty());
  command->add_option("--duration", run.duration, "simulated seconds")->check(FiniteRange(0.001, kMaxRunSeconds));
  command->add_option("--out", run.outDir, "output folder (created if missing)");
  command->add_option("--ply-every", run.plyEvery, "write a PLY mesh every N frames, 0 for none")
      ->transform(WholeNumber(0, 1000000));
  command->add_option("--images-every", run.imageEvery, "write a thickness image (PNG) every N frames, 0 for none")
      ->transform(WholeNumber(0, 1000000));
  command->add_option("--tool", line.tool, "bubble tool")->check(CLI::IsMember({"two-wands", "ring"}));
  addInputOptions(command, run.input);  // --input, --gesture and the capture options
  addBubbleOptions(command, run.input);
  command->add_option("--speed", run.gestureOptions.speed, "peak wand speed (m/s)")->check(FiniteRange(0.0, 20.0));
  command->add_option("--solution", run.params.solution, "remaining soap solution (0, 1]")
      ->check(FiniteRange(0.01, 1.0));
  command->add_option("--particles", run.params.particlesAtFullSolution, "particles of a film at full solution")
      ->transform(WholeNumber(16, kMaxParticles));
  command->add_option("--param", line.assignments, "set a model parameter, NAME=VALUE (repeatable)");
  command
      ->add_option("--burst-at", run.burstAt,
                   "poke the top of the film at this time (s), whatever the input; negative: never")
      ->check(FiniteRange(kNeverBurst, kMaxRunSeconds));
  command->add_flag("!--no-progress", run.progress, "do not show the progress bar");
  command->add_flag("--realtime", run.realtime,
                    "keep the wall clock: wait when ahead of it, take fewer solver sweeps when behind (a show's pace)");
  command->add_option("--osc", run.osc, "send events and the bubble's size and position as OSC to HOST:PORT (UDP)")
      ->check(NotEmpty());
  command->add_option("--backend", line.backend, "cpu, vulkan, or auto (Vulkan on a GPU, else the CPU)")
      ->check(CLI::IsMember({"cpu", "vulkan", "auto"}));
  command->add_option("--device", run.device,
                      "Vulkan device: index or part of its name (default: $GIANTBUBBLE_VULKAN_DEVICE, else the best)");
  command
      ->add_option("--between-steps", line.betweenSteps,
                   "Vulkan backend: where the contact search, the statistics and the film checks run: device, cpu, or "
                   "auto (the device unless it is a CPU driver)")
      ->check(CLI::IsMember({"auto", "device", "cpu"}));
  addRenderOptions(*command, run.render);
  return command;
}

void resolveRunCommandLine(RunCommandLine& line, const CLI::App& command) {
  RunOptions& run = line.options;
  run.tool.kind = line.tool == "ring" ? ToolKind::Ring : ToolKind::TwoWands;
  // A recorded input's own length, unless --duration or a scene gives one.
  run.durationFromInput = command.count("--duration") == 0 && line.scene.empty();
  if (command.count("--burst-at") > 0) run.burstOnAnyInput = true;
  run.backend = backendFromName(line.backend);
  run.betweenSteps = workPlaceFromName(line.betweenSteps);
  // A scene's own video (the default scene's) is made where a Vulkan device allows, with a note where not;
  // --render asks for it and fails without one.
  run.renderIfPossible = command.count("--render") == 0;
}

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
