#include "view_command.h"

#include <CLI/CLI.hpp>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <utility>

#include "cli_checks.h"
#include "cpu_stepper.h"
#include "interrupt.h"
#include "live_camera.h"
#include "osc_cues.h"
#include "osc_events.h"
#include "performance_loop.h"
#include "performer_view.h"
#include "realtime_pacer.h"
#include "run_output.h"
#include "scripted_gestures.h"
#include "thread_policy.h"
#include "video_stream.h"
#include "vulkan_stepper.h"
#include "window.h"

namespace gb {

CLI::App* addViewCommand(CLI::App& app, ViewOptions& o) {
  CLI::App* cmd = app.add_subcommand("live",
                                     "perform live in a window: the wands follow --input (mouse: orbit, zoom; "
                                     "keys: R reset, D dip, B burst, Space pause, C colouring, F full screen, V "
                                     "performer view, O operator overlay, Home camera, 1-9 presets, Esc quit)");
  cmd->alias("view");
  // --input also takes "mouse" here: the left and right buttons drag the hands, the wheel pushes them.
  cmd->add_option("--scene", o.run.scene, "a built-in scene or a scene file (.toml); the other options change it")
      ->check(NotEmpty());
  cmd->add_option("--tool", o.tool, "bubble tool")->check(CLI::IsMember({"two-wands", "ring"}));
  addInputOptions(cmd, o.run.input);  // --input kinect|fakenect:DIR|trajectory:FILE|script:NAME, --gesture, ...
  cmd->add_option("--param", o.assignments, "set a model parameter, NAME=VALUE (repeatable)");
  cmd->add_option("--osc", o.run.osc,
                  "send events, the bubble's size and position and the hands as OSC to HOST:PORT (UDP)")
      ->check(NotEmpty());
  cmd->add_option("--osc-in", o.oscIn,
                  "take cues as OSC on this UDP port: /giantbubble/dip, burst, reset, pause, colouring, camera, "
                  "fullscreen, performer_view, operator, quit")
      ->transform(WholeNumber(1, 65535));
  cmd->add_flag("--fullscreen", o.fullscreen, "full screen (borderless, at the monitor's resolution); F toggles");
  cmd->add_flag("--operator", o.operatorOverlay,
                "start with the operator overlay on: the show's messages over the window (never in the stream); O "
                "toggles it");
  cmd->add_option("--monitor", o.monitor, "the monitor for full screen, from 0 (the primary)")
      ->transform(WholeNumber(0, 63));
  cmd->add_option("--stream", o.stream,
                  "send the picture through ffmpeg to udp://HOST:PORT, srt://HOST:PORT, tcp://HOST:PORT (MPEG-TS), "
                  "rtmp://HOST/APP/KEY or a v4l2 device /dev/videoN")
      ->check([](const std::string& url) {
        try {
          (void)streamArguments(url, 16, 16);
          return std::string();
        } catch (const std::invalid_argument& e) {
          std::string why = e.what();  // "--stream 'URL': ...": CLI11 names the option itself
          return why.rfind("--stream ", 0) == 0 ? why.substr(9) : why;
        }
      });
  cmd->add_option("--auto-dip", o.autoDip, "seconds without a film before the wands dip again (negative: never)")
      ->check(FiniteRange(-1e9, 86400.0));
  cmd->add_option("--particles", o.run.params.particlesAtFullSolution, "particles of a film at full solution")
      ->transform(WholeNumber(16, kMaxParticles));
  cmd->add_option("--solution", o.run.params.solution, "remaining soap solution (0, 1]")->check(FiniteRange(0.01, 1.0));
  cmd->add_option("--backend", o.backend, "cpu, vulkan (on the window's device), or auto (Vulkan on a GPU)")
      ->check(CLI::IsMember({"cpu", "vulkan", "auto"}));
  cmd->add_option("--device", o.run.device, "Vulkan device: index or part of its name");
  cmd->add_option("--between-steps", o.betweenSteps,
                  "Vulkan backend: where the contact search, the statistics and the film checks run: device, cpu, or "
                  "auto (the device unless it is a CPU driver)")
      ->check(CLI::IsMember({"auto", "device", "cpu"}));
  cmd->add_option("--frames", o.frames, "quit after this many frames (0: when the window closes)")
      ->transform(WholeNumber(0, 100000000));
  cmd->add_option("--keys", o.keys,
                  "scripted key presses FRAME:KEY, e.g. 50:b 80:c (keys r d b p c f v o, h for Home, 1-9 a preset; "
                  "for tests and demos)")
      ->check([](const std::string& s) {
        std::string why;
        return parseKeyPress(s, why) ? std::string() : why;
      });
  cmd->add_flag("--fixed-step", o.fixedStep,
                "advance one 0.02 s frame per presented frame instead of keeping the wall clock (slow motion on a slow "
                "machine)");
  cmd->add_option("--min-sweeps", o.minSweeps, "fewest solver sweeps per frame when the machine cannot keep up")
      ->transform(WholeNumber(1, 1000));
  cmd->add_option(
         "--longest-step", o.longestStep,
         "frames of time one implicit step may cover when the machine cannot keep up (1: every step one frame)")
      ->transform(WholeNumber(1, 5));
  addControlOptions(*cmd, o.control);  // --control, --control-bind, --control-token, --presets
  addRenderOptions(*cmd, o.run.render, RenderedFiles::None);
  return cmd;
}

namespace {

// The stepper for the view: the Vulkan stepper shares the window's device, so the renderer reads its buffers.
std::unique_ptr<Stepper> viewStepper(const std::string& backend, const std::shared_ptr<const VulkanContext>& context,
                                     const std::string& betweenSteps) {
  const bool gpu = context->info().type != "CPU";
  if (backend != "vulkan" && !(backend == "auto" && gpu)) return std::make_unique<CpuStepper>();
  VulkanStepperOptions options;
  options.contactSearch = options.statistics = workPlaceFromName(betweenSteps);
  return std::make_unique<VulkanStepper>(context, options);
}

// The wands' input: the mouse (the window's pointer moves a PointerHandSource, read through the stabilizer
// like a camera) or any input makeWandInput opens. A new mouse input takes the window's pointer from the old.
std::unique_ptr<WandInput> makeLiveInput(const RunOptions& run, Window& window, const PerformerWait& waiting,
                                         const HandSourceWrapper& wrap) {
  if (run.input.spec() != "mouse") return makeWandInput(run.input, run.gestureOptions, waiting, wrap);
  const Calibration calibration = calibrationOf(run.input);
  auto pointer = std::make_unique<PointerHandSource>(calibration);
  PointerHandSource* hands = pointer.get();
  constexpr double metresPerNotch = 0.05;  // the wheel pushes the held hands 5 cm per notch
  window.setPointerListener(
      {[hands](double x, double y) { hands->setPointer(x, y); },
       [hands](int hand, bool down) { hands->setButton(hand == 0 ? Hand::Left : Hand::Right, down); },
       [hands](double notches) { hands->pushHands(metresPerNotch * notches); }});
  return std::make_unique<StabilizedWands>(std::move(pointer), stabilizerOptionsOf(run.input), calibration);
}

// The wands held still where they are: the input when one could not be opened again (a recording removed since).
class RestingWands : public WandInput {
 public:
  explicit RestingWands(const WandState& wands) : wands_(wands) {
    wands_.leftVelocity = wands_.rightVelocity = Vec3::Zero();
  }
  WandFrame at(double) override { return {wands_}; }
  [[nodiscard]] std::string describe() const override { return "the wands at rest (no input)"; }
  [[nodiscard]] bool ended() const override { return true; }

 private:
  WandState wands_;
};

// While a camera input waits for a performer the window stays alive: it shows the stage without a film, the wait's
// message and the performer view a few times a second; `service` handles the keys and cues meanwhile (Esc/Q, F, V,
// closing the window or Ctrl-C end the show).
class PerformerWaitScreen {
 public:
  // `tell` takes each of the wait's messages (the console, the operator overlay, the performer view, OSC).
  PerformerWaitScreen(Window& window, Renderer& renderer, std::function<bool()> service, MessageSink tell)
      : window_(window), renderer_(renderer), service_(std::move(service)), tell_(std::move(tell)) {}

  // A live camera's performer goes through the set-up step: both hands held forward and still for this long.
  static constexpr double kSetUpSeconds = 1.5;
  [[nodiscard]] PerformerWait hooks(bool liveCamera) {
    PerformerWait wait;
    wait.say = tell_;
    wait.cancelled = [this] { return pollAndRedraw(); };
    wait.holdStill = liveCamera ? kSetUpSeconds : 0.0;
    return wait;
  }
  [[nodiscard]] bool quit() const { return quit_; }
  [[nodiscard]] long redrawn() const { return redrawn_; }

 private:
  static constexpr std::chrono::milliseconds kRedrawEvery{200};
  bool pollAndRedraw() {
    quit_ = quit_ || service_() || InterruptCatcher::requested();
    const auto now = std::chrono::steady_clock::now();
    if (!quit_ && now - lastRedraw_ >= kRedrawEvery) {
      RenderFrame stage;
      stage.film = &noFilm_;
      stage.camera = window_.camera();
      window_.present(renderer_, stage);
      lastRedraw_ = now;
      ++redrawn_;
    }
    return quit_;
  }
  Window& window_;
  Renderer& renderer_;
  std::function<bool()> service_;
  MessageSink tell_;
  const Film noFilm_;
  bool quit_ = false;
  long redrawn_ = 0;
  std::chrono::steady_clock::time_point lastRedraw_;
};

// The keys of --keys and the actions they stand for: the window's keys and the OSC cues act the same.
constexpr std::pair<char, CueAction> kScriptedKeys[] = {
    {'r', CueAction::Reset},         {'d', CueAction::Dip},       {'b', CueAction::Burst},
    {'p', CueAction::Pause},         {'c', CueAction::Colouring}, {'f', CueAction::Fullscreen},
    {'v', CueAction::PerformerView}, {'o', CueAction::Operator},  {'h', CueAction::Camera}};

// The window's flag of each action.
constexpr std::pair<CueAction, bool WindowKeys::*> kFlags[] = {{CueAction::Dip, &WindowKeys::dip},
                                                               {CueAction::Burst, &WindowKeys::burst},
                                                               {CueAction::Reset, &WindowKeys::reset},
                                                               {CueAction::Pause, &WindowKeys::pause},
                                                               {CueAction::Colouring, &WindowKeys::nextColouring},
                                                               {CueAction::Camera, &WindowKeys::resetCamera},
                                                               {CueAction::Fullscreen, &WindowKeys::fullscreen},
                                                               {CueAction::PerformerView, &WindowKeys::performerView},
                                                               {CueAction::Operator, &WindowKeys::operatorOverlay},
                                                               {CueAction::Quit, &WindowKeys::quit}};
bool& flagOf(WindowKeys& keys, CueAction action) {
  for (const auto& [a, flag] : kFlags)
    if (a == action) return keys.*flag;
  return keys.quit;  // every action is in the table
}

// Adds the scripted key presses of frame `frame` to what the window reported.
void addScriptedKeys(const std::vector<std::string>& script, long frame, WindowKeys& keys) {
  std::string why;
  for (const std::string& entry : script) {
    const auto press = parseKeyPress(entry, why);
    if (!press || press->frame != frame) continue;
    for (const auto& [key, action] : kScriptedKeys)
      if (key == press->key) flagOf(keys, action) = true;
    if (press->key >= '1' && press->key <= '9') keys.preset = press->key - '0';
  }
}

// The live figures: presented frames per second, real-time factor, simulation and render ms, solver sweeps.
std::string liveFigures(const RealTimePacer& pacer, long shown, std::chrono::steady_clock::time_point start,
                        std::chrono::steady_clock::time_point now) {
  const double seconds = std::max(std::chrono::duration<double>(now - start).count(), 1e-9);
  char text[160];
  std::snprintf(text, sizeof text,
                "giantbubble  %.1f fps  real time x%.2f  sim %.1f ms  render %.1f ms at %.0f%%  %d sweeps%s",
                static_cast<double>(shown) / seconds, pacer.realTimeFactor(now), pacer.simMs(), pacer.renderMs(),
                100.0 * pacer.renderScale(), pacer.sweeps(), pacer.atFloor() ? " (floor)" : "");
  return text;
}
// The show's figures while a film is on the wands or in the air. An empty stage after a burst draws and keeps time
// easily: figures over the whole show would hide how it runs while there is something to see.
struct FilmShownTally {
  long presented = 0, simulated = 0, sweeps = 0;
  double wallSeconds = 0;

  void add(int frames, int sweepsTaken, double seconds) {
    ++presented;
    simulated += frames;
    sweeps += static_cast<long>(sweepsTaken) * frames;
    wallSeconds += seconds;
  }
  [[nodiscard]] std::string describe(double frameTime) const {
    if (presented == 0) return "no film was shown";
    char text[200];
    std::snprintf(text, sizeof text,
                  "while a film was shown: %ld frames presented in %.2f s (%.1f frames/s), real time x%.2f, %.1f "
                  "sweeps a frame",
                  presented, wallSeconds, static_cast<double>(presented) / std::max(wallSeconds, 1e-9),
                  static_cast<double>(simulated) * frameTime / std::max(wallSeconds, 1e-9),
                  static_cast<double>(sweeps) / static_cast<double>(std::max(simulated, 1L)));
    return text;
  }
};

// How often the film was in the picture while it was on stage: its centre inside the image.
struct InPictureTally {
  long frames = 0, inside = 0;
  void add(const OrbitCamera& camera, float aspect, const State& film) {
    bool any = false;
    for (size_t i = 0; i < film.size() && !any; ++i) any = film.alive[i] != 0;
    if (!any) return;
    const Eigen::Vector2f p = pictureCoordinates(camera, aspect, centroid(film));
    ++frames;
    if (std::abs(p.x()) <= 1.0f && std::abs(p.y()) <= 1.0f) ++inside;
  }
};

// A camera that was unplugged is looked for again this often (s of wall time); a recording or a file that
// ended plays again once the stage is empty (PerformanceLoop), or when R restarts it.
constexpr double kReopenCameraEvery = 2.0;

}  // namespace

std::optional<KeyPress> parseKeyPress(const std::string& text, std::string& why) {
  const auto colon = text.find(':');
  std::string keys;
  for (const auto& [key, action] : kScriptedKeys) keys += std::string(keys.empty() ? "" : " ") + key;
  why = "expected FRAME:KEY with KEY one of " + keys + " or a digit 1-9 (a preset), got '" + text + "'";
  const bool digit = !text.empty() && text.back() >= '1' && text.back() <= '9';
  if (colon == std::string::npos || colon == 0 || text.size() != colon + 2 ||
      (keys.find(text.back()) == std::string::npos && !digit) || text.back() == ' ')
    return std::nullopt;
  KeyPress press{0, text.back()};
  const char* end = text.data() + colon;
  const auto [ptr, ec] = std::from_chars(text.data(), end, press.frame);
  if (ec == std::errc() && ptr == end && press.frame < 0) {
    why = "--keys " + text + ": frame " + text.substr(0, colon) + " is negative (frames count from 0)";
    return std::nullopt;
  }
  if (ec == std::errc::result_out_of_range || (ec == std::errc() && press.frame > kMaxKeyFrame)) {
    why = "--keys " + text + ": frame " + text.substr(0, colon) + " is too large (at most " +
          std::to_string(kMaxKeyFrame) + ")";
    return std::nullopt;
  }
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return press;
}

int runView(ViewOptions o) try {
  RunOptions& run = o.run;
  run.input.wallClock = true;  // the show keeps the wall clock: a camera's hands are never waited for
  run.tool.kind = o.tool == "ring" ? ToolKind::Ring : ToolKind::TwoWands;
  ShowControl show(run.osc);
  std::unique_ptr<OscCueReceiver> cues;
  if (o.oscIn > 0 || o.control.port >= 0) {  // --control alone: OSC on a free port, for the page and HOST_INFO
    cues = std::make_unique<OscCueReceiver>(o.oscIn);
    std::printf("live: taking OSC cues on UDP port %d (/giantbubble/dip, burst, reset, pause, ...)\n", cues->port());
    std::fflush(stdout);
  }
  // Parameters over OSC, presets, OSCQuery and the control page (control/live_control.h).
  std::unique_ptr<LiveControl> control;
  if (cues) control = std::make_unique<LiveControl>(o.control, run.params, *cues);
  if (control && !control->describe().empty()) std::printf("live: %s\n", control->describe().c_str());
  RenderOptions image = run.render.image;
  Window window("giantbubble", image.width, image.height, run.device, {o.fullscreen, o.monitor});
  // The show's image: the window's size, or the monitor's in full screen (dynamic resolution draws less of it).
  const std::array<int, 2> windowedSize{image.width, image.height};
  auto showSize = [&] { return window.fullscreen() ? window.size() : windowedSize; };
  image.width = showSize()[0];
  image.height = showSize()[1];
  if (window.fullscreen())
    std::printf("live: full screen on %s, drawing at %dx%d\n", window.monitorDescription().c_str(), image.width,
                image.height);
  image.samples = samplesFor(run.render, window.context()->info().type);
  const InterruptCatcher interrupts;  // Ctrl-C ends the show as Esc does, with its totals
  Renderer renderer(window.context(), image, loadEnvironment(run.render.environment));
  // The stream has the show's own size (--width, --height), whatever the window's: in full screen on a large monitor,
  // a stream of the monitor's size would cost the show an encoder of that size (at 1920x1080 on two cores, 30% of
  // the frame rate); --width and --height ask for a larger stream.
  std::unique_ptr<VideoStream> stream;
  if (!o.stream.empty()) {
    const auto [width, height] = windowedSize;
    stream = std::make_unique<VideoStream>(o.stream, width, height);
    window.captureFrames(width, height);
    std::printf("live: streaming %dx%d to %s through ffmpeg\n", width, height, o.stream.c_str());
  }
  LiveCamera camera(run.render.camera, run.render.followCamera,
                    static_cast<float>(image.width) / static_cast<float>(image.height));
  window.camera() = run.render.camera;
  PerformerView performerView;
  std::optional<RealTimePacer> pacer;  // made once the show starts
  const double floorScale = o.fixedStep ? 1.0 : o.minRenderScale;

  auto say = [&control](long frame, const std::string& what) {
    std::printf("live: frame %ld: %s\n", frame, what.c_str());
    std::fflush(stdout);
    if (control) control->lastEvent(what);
  };
  // F: the picture goes full screen or back, the image drawn at its new size.
  auto toggleFullscreen = [&](long frame) {
    window.setFullscreen(!window.fullscreen());
    const auto [width, height] = showSize();
    camera.setAspect(static_cast<float>(width) / static_cast<float>(height));
    if (pacer) pacer->setMinRenderScale(o.fixedStep ? 1.0 : renderScaleFloor(floorScale, width, height));
    renderer.resize(width, height);
    std::string now = window.fullscreen() ? "full screen on " : "a window";
    if (window.fullscreen()) now += window.monitorDescription();
    now += ", drawing at ";
    now += std::to_string(width);
    now += 'x';
    now += std::to_string(height);
    say(frame, now);
  };
  // The cues that came in, as the keys they stand for; `fromCue` marks the ones a cue asked for, to report them.
  WindowKeys fromCue;
  int pauseCue = -1;  // /pause with an argument: 1 pause, 0 resume
  auto takeCues = [&](WindowKeys& keys) {
    fromCue = {};
    pauseCue = -1;
    if (!cues) return;
    for (const Cue& cue : cues->poll()) {
      flagOf(keys, cue.action) = flagOf(fromCue, cue.action) = true;
      if (cue.action == CueAction::Pause) pauseCue = cue.state;
    }
    for (const std::string& m : cues->takeMessages()) std::fprintf(stderr, "%s\n", m.c_str());
  };
  // What a cue did goes back out through OSC, and to the console.
  // `keyText` is what a key did in the console's words; `done`, a cue's, when they differ.
  auto reportCue = [&](long frame, bool cued, CueAction action, const std::string& keyText, double time,
                       const std::string& done = {}) {
    const std::string cueText = done.empty() ? keyText : done;
    say(frame, cued ? std::string("cue ") + cueName(action) + ": " + cueText : keyText);
    if (cued) show.cue(cueName(action), cueText, time);
  };
  // O: the operator overlay (the show's messages over the window, never in the stream) on or off.
  window.setOperatorOverlay(o.operatorOverlay);
  auto toggleOperatorOverlay = [&]() -> std::string {
    window.setOperatorOverlay(!window.operatorOverlay());
    return window.operatorOverlay() ? "operator overlay on" : "operator overlay off";
  };
  // The performer view's newest picture into the window's inset.
  bool viewTold = false;
  auto updateInset = [&] {
    if (performerView.shown() && !viewTold) {
      std::printf("live: the performer view shows what the camera sees (V hides it)\n");
      std::fflush(stdout);
      viewTold = true;
    }
    if (std::optional<RgbImage> view = performerView.update()) window.setInset(view->width, view->height, view->rgb);
  };

  // While a performer is waited for: the keys and cues that matter then.
  long waitFrames = 0;
  auto serviceWhileWaiting = [&] {
    WindowKeys keys = window.poll();
    takeCues(keys);
    performerView.setWaiting(true);
    if (keys.fullscreen) toggleFullscreen(waitFrames);
    if (keys.performerView)
      reportCue(waitFrames, fromCue.performerView, CueAction::PerformerView, performerView.toggle(), 0.0);
    if (keys.operatorOverlay)
      reportCue(waitFrames, fromCue.operatorOverlay, CueAction::Operator, toggleOperatorOverlay(), 0.0);
    updateInset();
    ++waitFrames;
    return keys.quit;
  };
  // The wait's messages: the console, the operator overlay, the performer (under the performer view) and OSC.
  const MessageSink tellWait = [&](const std::string& message) {
    printToStderr(message);
    window.showMessage(message);
    const std::string prefix = "waiting for a performer: ";
    performerView.setCaption(message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message);
    show.performer("waiting", message);
  };
  PerformerWaitScreen waiting(window, renderer, serviceWhileWaiting, tellWait);
  // A camera's depth frames are kept for the performer view.
  const HandSourceWrapper observe = [&](std::unique_ptr<HandSource> source) -> std::unique_ptr<HandSource> {
    auto observed = std::make_unique<ObservedHandSource>(std::move(source));
    performerView.attach(observed.get());
    return observed;
  };
  // The input, waiting for a performer where it is a camera's (the performer view shows meanwhile).
  auto openInput = [&] {
    performerView.attach(nullptr);  // the source it shows goes with the input
    try {
      std::unique_ptr<WandInput> opened =
          makeLiveInput(run, window, waiting.hooks(run.input.spec() == "kinect"), observe);
      performerView.setWaiting(false);
      performerView.setCaption("");
      if (opened->performerFound()) show.performer("found", opened->describe());
      return opened;
    } catch (...) {
      performerView.setWaiting(false);
      throw;
    }
  };
  std::unique_ptr<WandInput> input = openInput();
  if (waiting.quit()) {
    std::printf("live: ended while waiting for a performer (the window was redrawn %ld times)\n", waiting.redrawn());
    return InterruptCatcher::exitStatus(0);
  }
  std::printf("live: input %s\n", input->describe().c_str());
  std::unique_ptr<Stepper> stepper = viewStepper(o.backend, window.context(), o.betweenSteps);
  const bool readInPlace = dynamic_cast<VulkanStepper*>(stepper.get()) != nullptr;
  std::printf("live: %s, %d sample%s per pixel, on %s (validation layer %s), simulation on %s\n",
              colouringName(image.colouring), image.samples, image.samples == 1 ? "" : "s",
              window.context()->info().name.c_str(), window.context()->validationEnabled() ? "on" : "off",
              stepper->name().c_str());
  std::fflush(stdout);
  double t = 0;
  WandFrame hands = input->at(t);
  WandState wands = hands.wands;
  auto sim = std::make_unique<Simulation>(run.params, run.tool, wands, std::move(stepper));
  show.frame(*sim, sim->stats(), "film_created");

  bool paused = false, quitRequested = false;
  long shown = 0, dips = 0, recoveries = 0, loops = 0;
  double filmGoneSince = -1;  // time the last film disappeared, -1 while there is one
  double inputStart = 0;      // show time at which the current input's time 0 is
  bool inputLost = false;
  bool freeBubble = false;  // the film on stage has pinched off: the wands hold none
  bool burstByCue = false;  // the poke of a cue: its burst is told as burst_by_cue
  // A script or a recording plays again once the stage is empty (performance_loop.h); a performer (a camera, the
  // mouse) dips again by themselves.
  const bool performer = run.input.spec() == "kinect" || run.input.spec() == "mouse";
  PerformanceLoop loop(performer ? -1.0 : o.autoDip);
  const double scriptEnd = static_cast<double>(run.gestureOptions.start) + run.gestureOptions.duration;
  auto performanceOver = [&] { return run.input.scripted() ? t - inputStart >= scriptEnd : input->ended(); };
  // The hands as OSC joints (camera space): the measured ones, or the wand tips of a script.
  const Calibration scriptCalibration = calibrationOf(run.input);
  auto sendHands = [&] {
    const auto* stabilized = dynamic_cast<const StabilizedWands*>(input.get());
    const Calibration& calibration = stabilized ? stabilized->calibration() : scriptCalibration;
    const Vec3 left = stabilized ? hands.leftHand : wands.leftPosition;
    const Vec3 right = stabilized ? hands.rightHand : wands.rightPosition;
    show.hands(calibration.toCamera(left.cast<double>()), calibration.toCamera(right.cast<double>()));
  };
  // The performer's state over OSC as it changes (a hand lost, both back), and what they should do on the console
  // when that changes (at most every 2 s: a hand flickering in and out does not flood it).
  std::array<bool, 2> handsLost{false, false};
  std::string advised;
  auto advisedAt = std::chrono::steady_clock::now() - std::chrono::seconds(10);
  auto tellPerformer = [&] {
    const std::array<bool, 2> lost = input->handsLost();
    for (int h = 0; h < 2; ++h)
      if (lost[h] && !handsLost[h]) show.performer(h == 0 ? "left_hand_lost" : "right_hand_lost", "");
    if (handsLost != lost && !lost[0] && !lost[1]) show.performer("hands_back", "");
    handsLost = lost;
    const std::string advice = performerView.advice();
    const auto now = std::chrono::steady_clock::now();
    if (advice != advised && now - advisedAt >= std::chrono::seconds(2)) {
      if (!advice.empty()) say(shown, "advice for the performer: " + advice);
      advised = advice;
      advisedAt = now;
    }
  };
  auto lastReopen = std::chrono::steady_clock::now();
  SimulationThreads threads;  // one fewer for each core another process keeps busy (thread_policy.h)
  const auto start = std::chrono::steady_clock::now();
  pacer.emplace(PacerOptions{run.params.frameTime, sim->solverSweeps(), o.minSweeps, 4,
                             o.fixedStep ? 1.0 : renderScaleFloor(floorScale, image.width, image.height)},
                start);
  auto lastTitle = start;
  auto lastPresented = start;
  FilmShownTally filmShown;
  InPictureTally inPicture;
  for (;;) {
    WindowKeys keys = window.poll();
    addScriptedKeys(o.keys, shown, keys);
    takeCues(keys);
    // Parameter sets and presets between frames; their reports to the console and OSC out.
    const LiveControl::Report reportControl = [&](const std::string& what) {
      say(shown, what);
      show.cue("param", what, t);
    };
    if (control && keys.preset > 0) control->recallNumbered(keys.preset);  // keys 1-9
    if (control) control->betweenFrames(*sim, reportControl);
    if (keys.quit || waiting.quit() || InterruptCatcher::requested()) {  // Esc/Q, closed, a cue, Ctrl-C, SIGTERM
      if (fromCue.quit) reportCue(shown, true, CueAction::Quit, "the show ends", t);
      break;
    }
    auto announce = [&](const std::string& what) {  // a fault the show recovers from: the console and the screen
      say(shown, what);
      window.showMessage(what);
    };
    auto dipNewFilm = [&](const std::string& why, const std::string& events) {
      if (control) control->beforeDip(*sim, reportControl);
      sim->dip(wands);
      filmGoneSince = -1;
      freeBubble = false;
      burstByCue = false;
      ++dips;
      show.frame(*sim, sim->stats(), events);
      return why;
    };
    // The input from its start: a new source, since time only moves forward in one. The old one is let go of
    // first: fakenect plays one recording at a time. One that cannot be opened again (a recording removed since)
    // leaves the wands at rest, and the show goes on.
    auto restartInput = [&]() {
      input.reset();
      try {
        input = openInput();
        inputLost = false;
      } catch (const HandSourceError& e) {
        input = std::make_unique<RestingWands>(wands);
        inputLost = true;
        announce(std::string("the input cannot be played again: ") + e.what() + "; the wands rest");
        show.frame(*sim, sim->stats(), "input_lost");
      }
      quitRequested = quitRequested || waiting.quit();
    };
    if (keys.fullscreen) {
      toggleFullscreen(shown);
      if (fromCue.fullscreen) show.cue("fullscreen", window.fullscreen() ? "full screen" : "a window", t);
    }
    if (keys.performerView)
      reportCue(shown, fromCue.performerView, CueAction::PerformerView, performerView.toggle(), t);
    if (keys.operatorOverlay)
      reportCue(shown, fromCue.operatorOverlay, CueAction::Operator, toggleOperatorOverlay(), t);
    if (keys.resetCamera) {
      camera.home();
      reportCue(shown, fromCue.resetCamera, CueAction::Camera,
                run.render.followCamera ? "the camera follows the film again" : "the scene's camera again", t);
    }
    if (keys.pause) {
      paused = pauseCue >= 0 ? pauseCue == 1 : !paused;
      reportCue(shown, fromCue.pause, CueAction::Pause, paused ? "paused" : "resumed", t);
    }
    if (keys.reset) {
      restartInput();
      if (quitRequested) break;
      inputStart = t;
      loop.restart();
      hands = input->at(0);
      wands = hands.wands;
    }
    // A performer's wands dip again by themselves once they are apart: a film dipped between closed tips would
    // only pinch off at once into a sliver. A script or a recording loops instead (PerformanceLoop).
    const bool wandsApart = run.tool.kind == ToolKind::Ring ||
                            (wands.rightPosition - wands.leftPosition).norm() > 2.0f * run.params.pinchDistance;
    const bool autoDip =
        performer && o.autoDip >= 0 && filmGoneSince >= 0 && t - filmGoneSince >= o.autoDip && wandsApart;
    if (keys.reset)
      reportCue(shown, fromCue.reset, CueAction::Reset,
                dipNewFilm("reset: new film, performance from its start", "film_created"), t,
                "new film, performance from its start");
    else if (keys.dip)
      reportCue(shown, fromCue.dip, CueAction::Dip, dipNewFilm("dip: new film", "film_created"), t, "new film");
    else if (autoDip)
      say(shown, dipNewFilm("auto dip: new film", "film_created"));
    if (keys.burst) {
      const bool poked = pokeTop(*sim);
      burstByCue = poked && fromCue.burst;
      reportCue(shown, fromCue.burst, CueAction::Burst, poked ? "burst" : "B: no film to burst", t,
                poked ? "burst" : "no film to burst");
    }
    if (keys.nextColouring) {
      renderer.setColouring(static_cast<Colouring>((static_cast<int>(renderer.options().colouring) + 1) % 3));
      reportCue(shown, fromCue.nextColouring, CueAction::Colouring, colouringName(renderer.options().colouring), t);
    }
    // The wands of show time t: the input's, or on their way back to its start while the performance loops.
    auto moveWands = [&] {
      switch (loop.next(t, performanceOver(), freeBubble || filmGoneSince >= 0, filmGoneSince)) {
        case PerformanceLoop::Action::StartReturn: {
          restartInput();
          const WandState from = wands;
          loop.startReturn(t, from, input->at(0).wands);
          char text[120];
          std::snprintf(text, sizeof text, "the performance is over: the wands go back to its start (%.1f s)",
                        loop.returnSeconds());
          say(shown, text);
          wands = loop.returnWands(t);
          return;
        }
        case PerformanceLoop::Action::Return:
          wands = loop.returnWands(t);
          return;
        case PerformanceLoop::Action::DipAndPlay:
          wands = loop.returnWands(t);
          inputStart = t;
          ++loops;
          say(shown, dipNewFilm("loop: new film, the performance from its start", "film_created"));
          return;
        case PerformanceLoop::Action::StartPlaying:
          inputStart = t;
          ++loops;
          say(shown, "loop: the performance from its start");
          [[fallthrough]];
        case PerformanceLoop::Action::Play:
          break;
      }
      hands = input->at(t - inputStart);  // a camera's newest hands: never waited for (input.wallClock)
      wands = hands.wands;
      for (const std::string& m : input->takeMessages()) {  // e.g. a camera's hands lost or found
        std::fprintf(stderr, "%s\n", m.c_str());
        window.showMessage(m);
      }
      tellPerformer();
      if (input->ended() && !inputLost && !loop.looping()) {
        inputLost = true;
        if (!performer) {  // a recording or a file played to its end: it plays again once the stage is empty
          say(shown, "the input has played to its end; the wands rest" +
                         std::string(o.autoDip >= 0 ? " until the stage is empty, then it plays again"
                                                    : " (R plays it again)"));
          return;
        }
        // The wands rest where they are (wand_input.h) until the input returns.
        announce("the input has ended or was lost; the wands rest" +
                 std::string(run.input.spec() == "kinect" ? ", and the camera is looked for again"
                                                          : " (R starts it again)"));
        show.frame(*sim, sim->stats(), "input_lost");
      }
    };
    // `frames` frames of h on the wall clock in one step (more than one when behind it): the input, then the
    // simulation; a simulation that blows up is replaced.
    auto advanceStep = [&](int frames) {
      t += static_cast<double>(run.params.frameTime) * frames;
      moveWands();
      sendHands();
      if (inputLost && run.input.spec() == "kinect" &&
          std::chrono::duration<double>(std::chrono::steady_clock::now() - lastReopen).count() >= kReopenCameraEvery) {
        lastReopen = std::chrono::steady_clock::now();
        try {
          input = openInput();
          inputStart = t;
          inputLost = false;
          announce("the camera is back");
          show.frame(*sim, sim->stats(), "input_back");
        } catch (const HandSourceError&) {  // not yet: the wands go on resting
        }
      }
      try {
        sim->setFrameTime(run.params.frameTime * static_cast<float>(frames));
        threads.update();
        sim->advanceFrame(wands);
        const FrameStats stats = sim->stats();
        std::string events = describeEvents(sim->lastEvents());
        if (const auto poke = events.find("burst_by_poke"); burstByCue && poke != std::string::npos) {
          events.replace(poke, std::string("burst_by_poke").size(), "burst_by_cue");
          burstByCue = false;
        }
        show.frame(*sim, stats, events);
        freeBubble = freeBubble || sim->lastEvents().pinchedOff;
        if (stats.particles == 0 && filmGoneSince < 0) filmGoneSince = t;
      } catch (const SimulationUnstable& e) {
        // The show goes on: the broken simulation is dropped whole (a dip keeps state the blow-up may have
        // poisoned, such as the air) and a new one starts with a film on the wands as they are.
        ++recoveries;
        std::fprintf(stderr, "warning: %s\n", e.what());
        sim = std::make_unique<Simulation>(run.params, run.tool, wands,
                                           viewStepper(o.backend, window.context(), o.betweenSteps));
        filmGoneSince = -1;
        freeBubble = false;
        ++dips;
        announce("the simulation became unstable; a new film is dipped");
        show.frame(*sim, sim->stats(), "simulation_unstable film_created");
      }
    };
    int due = 0;
    double simMs = 0;
    if (paused) {
      pacer->resync();
    } else {
      due = o.fixedStep ? 1 : pacer->framesDue();
      if (due == 0) {  // ahead of the wall clock: wait for the next frame rather than draw the same one twice
        pacer->sleepUntilDue();
        due = pacer->framesDue();
      }
      sim->setSolverSweeps(o.fixedStep ? 0 : pacer->sweeps());
      const auto simStart = std::chrono::steady_clock::now();
      // The frames due in steps of at most longestStep frames: a long step costs what a short one does, so a
      // machine that is behind halves its simulation work before the solver's sweeps go down.
      const int longest = run.params.integrator != 0 ? o.longestStep : 1;  // explicit: substeps would grow instead
      for (int done = 0; done < due && !quitRequested;) {
        const int frames = std::min(longest, due - done);
        advanceStep(frames);
        done += frames;
      }
      simMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - simStart).count();
      if (quitRequested) break;  // Esc or Ctrl-C while an input restarted waited for a performer
    }
    const auto renderStart = std::chrono::steady_clock::now();
    // The window's blit scales the image to the window (dynamic resolution).
    const auto [width, height] = showSize();
    renderer.resize(std::max(16, static_cast<int>(std::lround(width * pacer->renderScale()))),
                    std::max(16, static_cast<int>(std::lround(height * pacer->renderScale()))));
    const State& drawn = filmToDraw(*sim, readInPlace).state;  // where the particles are
    const OrbitCamera view =
        camera.update(drawn, wands, run.params.frameTime * static_cast<float>(due), window.camera(), keys.cameraMoved);
    if (filmGoneSince < 0) inPicture.add(view, camera.aspect(), drawn);
    updateInset();
    const WireFrame wire = sim->wireFrame(wands);
    DeviceFilm deviceFilm;
    window.present(renderer, renderFrameOf(*sim, wire, view, readInPlace, deviceFilm));
    if (stream) {
      stream->offer(window.captured());
      for (const std::string& m : stream->takeMessages()) std::fprintf(stderr, "warning: %s\n", m.c_str());
    }
    const auto now = std::chrono::steady_clock::now();
    pacer->record(due, simMs, std::chrono::duration<double, std::milli>(now - renderStart).count());
    if (filmGoneSince < 0 && !paused)
      filmShown.add(due, sim->solverSweeps(), std::chrono::duration<double>(now - lastPresented).count());
    lastPresented = now;
    if (control)
      control->publish(*sim, t, paused,
                       filmGoneSince >= 0 ? "none"
                       : freeBubble       ? "free_bubble"
                                          : "on_wands",
                       performer ? (input->performerFound() ? "found" : "waiting") : "none");
    if (now - lastTitle > std::chrono::seconds(1)) {  // the show's figures in the title bar, once a second
      window.setTitle(liveFigures(*pacer, shown, start, now));
      lastTitle = now;
    }
    if (++shown == o.frames) break;
  }
  const auto end = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(end - start).count();
  const size_t errors = window.context()->validationErrors();
  std::printf("live: %s, %ld frames simulated, %ld dropped\n", liveFigures(*pacer, shown, start, end).c_str(),
              pacer->simulatedFrames(), pacer->droppedFrames());
  std::printf(
      "live: presented %ld frames in %.2f s (%.1f frames/s), %ld dips, %zu validation errors, %ld recoveries "
      "from instability\n",
      shown, seconds, static_cast<double>(shown) / std::max(seconds, 1e-9), dips, errors, recoveries);
  std::printf("live: %s\n", filmShown.describe(run.params.frameTime).c_str());
  std::printf(
      "live: a film was on stage for %.1f%% of the show's wall time (%.1f of %.1f s); the performance "
      "played again %ld times\n",
      100.0 * filmShown.wallSeconds / std::max(seconds, 1e-9), filmShown.wallSeconds, seconds, loops);
  if (inPicture.frames > 0)
    std::printf("live: the film's centre was in the picture on %ld of the %ld frames it was on stage (%.1f%%)\n",
                inPicture.inside, inPicture.frames,
                100.0 * static_cast<double>(inPicture.inside) / static_cast<double>(inPicture.frames));
  if (cues)
    std::printf("live: OSC cues: %ld taken, %ld unknown and %ld malformed ignored\n", cues->taken(), cues->unknown(),
                cues->malformed());
  if (control) std::printf("live: %s\n", control->totals().c_str());
  if (stream) {
    const long sent = stream->sent();
    stream.reset();  // ends ffmpeg: what it sent is counted
    std::printf("live: stream: %ld frames sent, %ld dropped\n", sent, shown - sent);
  }
  if (const Simulation::BudgetRecord& budget = sim->energyBudgetRecord(); budget.frames > 0)
    std::printf(
        "live: the implicit step's energy budget took energy back on %ld steps (smallest factor on the "
        "wobble %.2f, most drift given back %.3f m/s; docs/model.md)\n",
        budget.frames, static_cast<double>(budget.smallestScale), static_cast<double>(budget.largestShift));
  return InterruptCatcher::exitStatus(errors == 0 ? 0 : 4);  // 130 or 143 after Ctrl-C or SIGTERM
} catch (const std::exception& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 1;
}

}  // namespace gb
