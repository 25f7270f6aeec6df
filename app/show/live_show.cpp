#include "app/show/live_show.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>
#include <utility>

#include "app/outputs/run_output.h"
#include "app/show/performer_touch.h"
#include "capture/scripted_gestures.h"
#include "host/vulkan_stepper.h"
#include "stages/cpu_stepper.h"

namespace gb {

namespace {

// The stepper for the show: the Vulkan stepper shares the window's device, so the renderer reads its buffers.
std::unique_ptr<Stepper> liveStepper(const std::string& backend, const std::shared_ptr<const VulkanContext>& context,
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
  WandFrame at(double) override {
    WandFrame frame;
    frame.wands = wands_;
    return frame;
  }
  [[nodiscard]] std::string describe() const override { return "the wands at rest (no input)"; }
  [[nodiscard]] bool ended() const override { return true; }

 private:
  WandState wands_;
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

// A camera that was unplugged is looked for again this often (s of wall time); a recording or a file that
// ended plays again once the stage is empty (PerformanceLoop), or when R restarts it.
constexpr double kReopenCameraEvery = 2.0;

// The show's options as it runs them: on the wall clock, with the tool named.
LiveOptions showOptions(LiveOptions o) {
  o.run.input.wallClock = true;  // the show keeps the wall clock: a camera's hands are never waited for
  o.run.tool.kind = o.tool == "ring" ? ToolKind::Ring : ToolKind::TwoWands;
  return o;
}

// The OSC cues taken on `port` (0: none; with --control alone, a free port, for the page and HOST_INFO).
std::unique_ptr<OscCueReceiver> openCues(int port, const ControlOptions& control) {
  if (port <= 0 && control.port < 0) return nullptr;
  auto cues = std::make_unique<OscCueReceiver>(port);
  std::printf("live: taking OSC cues on UDP port %d (/giantbubble/dip, burst, reset, pause, ...)\n", cues->port());
  std::fflush(stdout);
  return cues;
}

}  // namespace

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

void LiveShow::FilmShownTally::add(int frames, int sweepsTaken, double seconds, double renderScale) {
  ++presented;
  simulated += frames;
  sweeps += static_cast<long>(sweepsTaken) * frames;
  wallSeconds += seconds;
  if (renderScale < 1.0) ++drawnSmaller;
  smallestScale = std::min(smallestScale, renderScale);
}

std::string LiveShow::FilmShownTally::describe(double frameTime) const {
  if (presented == 0) return "no film was shown";
  char text[260];
  const int written = std::snprintf(
      text, sizeof text,
      "while a film was shown: %ld frames presented in %.2f s (%.1f frames/s), real time x%.2f, %.1f sweeps a frame",
      presented, wallSeconds, static_cast<double>(presented) / std::max(wallSeconds, 1e-9),
      static_cast<double>(simulated) * frameTime / std::max(wallSeconds, 1e-9),
      static_cast<double>(sweeps) / static_cast<double>(std::max(simulated, 1L)));
  if (drawnSmaller > 0 && written > 0 && static_cast<size_t>(written) < sizeof text)
    std::snprintf(text + written, sizeof text - static_cast<size_t>(written),
                  ", %ld drawn smaller than the window (down to %.0f%% of its width and height)", drawnSmaller,
                  100.0 * smallestScale);
  return text;
}

void LiveShow::InPictureTally::add(const OrbitCamera& camera, float aspect, const State& film) {
  bool any = false;
  for (size_t i = 0; i < film.size() && !any; ++i) any = film.alive[i] != 0;
  if (!any) return;
  const Eigen::Vector2f p = pictureCoordinates(camera, aspect, centroid(film));
  ++frames;
  if (std::abs(p.x()) <= 1.0f && std::abs(p.y()) <= 1.0f) ++inside;
}

LiveShow::LiveShow(LiveOptions options)
    : o_(showOptions(std::move(options))),
      run_(o_.run),
      show_(run_.osc),
      cues_(openCues(o_.oscIn, o_.control)),
      control_(cues_ ? std::make_unique<LiveControl>(o_.control, run_.params, *cues_) : nullptr),
      image_(run_.render.image),
      window_("giantbubble", image_.width, image_.height, run_.device, {o_.fullscreen, o_.monitor}),
      windowedSize_{image_.width, image_.height},
      floorScale_(o_.fixedStep ? 1.0 : o_.minRenderScale),
      performer_(run_.input.spec() == "kinect" || run_.input.spec() == "mouse"),
      loop_(performer_ ? -1.0 : o_.autoDip),
      scriptEnd_(static_cast<double>(run_.gestureOptions.start) + run_.gestureOptions.duration) {
  // The show's image: the window's size, or the monitor's in full screen (dynamic resolution draws less of it).
  image_.width = showSize()[0];
  image_.height = showSize()[1];
  if (window_.fullscreen())
    std::printf("live: full screen on %s, drawing at %dx%d\n", window_.monitorDescription().c_str(), image_.width,
                image_.height);
  image_.samples = samplesFor(run_.render, window_.context()->info().type);
  renderer_ = std::make_unique<Renderer>(window_.context(), image_, loadEnvironment(run_.render.environment));
  // The stream has the show's own size (--width, --height), whatever the window's: in full screen on a large monitor,
  // a stream of the monitor's size would cost the show an encoder of that size (at 1920x1080 on two cores, 30% of
  // the frame rate); --width and --height ask for a larger stream.
  if (!o_.stream.empty()) {
    const auto [width, height] = windowedSize_;
    stream_ = std::make_unique<VideoStream>(o_.stream, width, height);
    window_.captureFrames(width, height);
    std::printf("live: streaming %dx%d to %s through ffmpeg\n", width, height, o_.stream.c_str());
  }
  camera_ = std::make_unique<LiveCamera>(run_.render.camera, run_.render.followCamera,
                                         static_cast<float>(image_.width) / static_cast<float>(image_.height));
  window_.camera() = run_.render.camera;
  if (control_ && !control_->describe().empty()) std::printf("live: %s\n", control_->describe().c_str());
  // O: the operator overlay (the show's messages over the window, never in the stream) on or off.
  window_.setOperatorOverlay(o_.operatorOverlay);
  waiting_ = std::make_unique<PerformerWaitScreen>(
      window_, *renderer_, [this] { return serviceWhileWaiting(); },
      [this](const std::string& message) { tellWait(message); });
}

LiveShow::~LiveShow() = default;

int LiveShow::run() {
  if (!setUp()) return InterruptCatcher::exitStatus(0);
  while (frame()) {
  }
  return finish();
}

std::array<int, 2> LiveShow::showSize() const { return window_.fullscreen() ? window_.size() : windowedSize_; }

std::unique_ptr<Stepper> LiveShow::newStepper() const {
  return liveStepper(o_.backend, window_.context(), o_.betweenSteps);
}

void LiveShow::say(long frame, const std::string& what) const {
  std::printf("live: frame %ld: %s\n", frame, what.c_str());
  std::fflush(stdout);
  if (control_) control_->lastEvent(what);
}

// A parameter set or a preset recalled (or refused): the console and OSC out.
void LiveShow::reportControl(const std::string& what) {
  say(shown_, what);
  show_.cue("param", what, t_);
}

// A fault the show recovers from: the console and the screen.
void LiveShow::announce(const std::string& what) {
  say(shown_, what);
  window_.showMessage(what);
}

// F: the picture goes full screen or back, the image drawn at its new size.
void LiveShow::toggleFullscreen(long frame) {
  window_.setFullscreen(!window_.fullscreen());
  const auto [width, height] = showSize();
  camera_->setAspect(static_cast<float>(width) / static_cast<float>(height));
  if (pacer_) pacer_->setMinRenderScale(o_.fixedStep ? 1.0 : renderScaleFloor(floorScale_, width, height));
  renderer_->resize(width, height);
  std::string now = window_.fullscreen() ? "full screen on " : "a window";
  if (window_.fullscreen()) now += window_.monitorDescription();
  now += ", drawing at ";
  now += std::to_string(width);
  now += 'x';
  now += std::to_string(height);
  say(frame, now);
}

// The cues that came in, added to the keys they stand for.
void LiveShow::takeCues(WindowKeys& keys) {
  fromCue_ = {};
  pauseCue_ = -1;
  if (!cues_) return;
  for (const Cue& cue : cues_->poll()) {
    flagOf(keys, cue.action) = flagOf(fromCue_, cue.action) = true;
    if (cue.action == CueAction::Pause) pauseCue_ = cue.state;
  }
  for (const std::string& m : cues_->takeMessages()) std::fprintf(stderr, "%s\n", m.c_str());
}

// What a cue did goes back out through OSC, and to the console. `keyText` is what a key did in the console's words;
// `done`, a cue's, when they differ.
void LiveShow::reportCue(long frame, bool cued, CueAction action, const std::string& keyText, double time,
                         const std::string& done) {
  const std::string cueText = done.empty() ? keyText : done;
  say(frame, cued ? std::string("cue ") + cueName(action) + ": " + cueText : keyText);
  if (cued) show_.cue(cueName(action), cueText, time);
}

std::string LiveShow::toggleOperatorOverlay() {
  window_.setOperatorOverlay(!window_.operatorOverlay());
  return window_.operatorOverlay() ? "operator overlay on" : "operator overlay off";
}

// The performer view's newest picture into the window's inset.
void LiveShow::updateInset() {
  if (performerView_.shown() && !viewTold_) {
    std::printf("live: the performer view shows what the camera sees (V hides it)\n");
    std::fflush(stdout);
    viewTold_ = true;
  }
  if (std::optional<RgbImage> view = performerView_.update()) window_.setInset(view->width, view->height, view->rgb);
}

// While a performer is waited for: the keys and cues that matter then. True when the show is to end.
bool LiveShow::serviceWhileWaiting() {
  WindowKeys keys = window_.poll();
  takeCues(keys);
  performerView_.setWaiting(true);
  if (keys.fullscreen) toggleFullscreen(waitFrames_);
  if (keys.performerView)
    reportCue(waitFrames_, fromCue_.performerView, CueAction::PerformerView, performerView_.toggle(), 0.0);
  if (keys.operatorOverlay)
    reportCue(waitFrames_, fromCue_.operatorOverlay, CueAction::Operator, toggleOperatorOverlay(), 0.0);
  updateInset();
  ++waitFrames_;
  return keys.quit;
}

// The wait's messages: the console, the operator overlay, the performer (under the performer view) and OSC.
void LiveShow::tellWait(const std::string& message) {
  printToStderr(message);
  window_.showMessage(message);
  const std::string prefix = "waiting for a performer: ";
  performerView_.setCaption(message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message);
  show_.performer("waiting", message);
}

// The input, waiting for a performer where it is a camera's (the performer view shows meanwhile). A camera's depth
// frames are kept for the performer view.
std::unique_ptr<WandInput> LiveShow::openInput() {
  performerView_.attach(nullptr);  // the source it shows goes with the input
  mirrorView_.attach(nullptr);
  const HandSourceWrapper observe = [this](std::unique_ptr<HandSource> source) -> std::unique_ptr<HandSource> {
    auto observed = std::make_unique<ObservedHandSource>(std::move(source));
    performerView_.attach(observed.get());
    mirrorView_.attach(observed.get());
    return observed;
  };
  try {
    std::unique_ptr<WandInput> opened =
        makeLiveInput(run_, window_, waiting_->hooks(run_.input.spec() == "kinect"), observe);
    performerView_.setWaiting(false);
    performerView_.setCaption("");
    if (opened->performerFound()) show_.performer("found", opened->describe());
    return opened;
  } catch (...) {
    performerView_.setWaiting(false);
    throw;
  }
}

// The input from its start: a new source, since time only moves forward in one. The old one is let go of first:
// fakenect plays one recording at a time. One that cannot be opened again (a recording removed since) leaves the
// wands at rest, and the show goes on.
void LiveShow::restartInput() {
  input_.reset();
  try {
    input_ = openInput();
    inputLost_ = false;
  } catch (const HandSourceError& e) {
    input_ = std::make_unique<RestingWands>(wands_);
    inputLost_ = true;
    announce(std::string("the input cannot be played again: ") + e.what() + "; the wands rest");
    show_.frame(*sim_, sim_->stats(), "input_lost");
  }
  quitRequested_ = quitRequested_ || waiting_->quit();
}

std::string LiveShow::dipNewFilm(const std::string& why, const std::string& events) {
  if (control_) control_->beforeDip(*sim_, [this](const std::string& what) { reportControl(what); });
  sim_->dip(wands_);
  filmGoneSince_ = -1;
  freeBubble_ = false;
  burstByCue_ = false;
  ++dips_;
  show_.frame(*sim_, sim_->stats(), events);
  return why;
}

bool LiveShow::performanceOver() const {
  return run_.input.scripted() ? t_ - inputStart_ >= scriptEnd_ : input_->ended();
}

// The hands as OSC joints (camera space): the measured ones, or the wand tips of a script.
void LiveShow::sendHands() {
  const auto* stabilized = dynamic_cast<const StabilizedWands*>(input_.get());
  const Calibration& calibration = stabilized ? stabilized->calibration() : scriptCalibration_;
  const Vec3 left = stabilized ? hands_.leftHand : wands_.leftPosition;
  const Vec3 right = stabilized ? hands_.rightHand : wands_.rightPosition;
  show_.hands(calibration.toCamera(left.cast<double>()), calibration.toCamera(right.cast<double>()));
}

// The performer's state over OSC as it changes (a hand lost, both back), and what they should do on the console
// when that changes (at most every 2 s: a hand flickering in and out does not flood it).
void LiveShow::tellPerformer() {
  const std::array<bool, 2> lost = input_->handsLost();
  for (int h = 0; h < 2; ++h)
    if (lost[h] && !handsLost_[h]) show_.performer(h == 0 ? "left_hand_lost" : "right_hand_lost", "");
  if (handsLost_ != lost && !lost[0] && !lost[1]) show_.performer("hands_back", "");
  handsLost_ = lost;
  const std::string advice = performerView_.advice();
  const auto now = std::chrono::steady_clock::now();
  if (advice != advised_ && now - advisedAt_ >= std::chrono::seconds(2)) {
    if (!advice.empty()) say(shown_, "advice for the performer: " + advice);
    advised_ = advice;
    advisedAt_ = now;
  }
}

bool LiveShow::setUp() {
  input_ = openInput();
  if (waiting_->quit()) {
    std::printf("live: ended while waiting for a performer (the window was redrawn %ld times)\n", waiting_->redrawn());
    return false;
  }
  std::printf("live: input %s\n", input_->describe().c_str());
  std::unique_ptr<Stepper> stepper = newStepper();
  filmOnDevice_ = dynamic_cast<VulkanStepper*>(stepper.get()) != nullptr;
  std::printf("live: %s, %d sample%s per pixel, on %s (validation layer %s), simulation on %s\n",
              colouringName(image_.colouring), image_.samples, image_.samples == 1 ? "" : "s",
              window_.context()->info().name.c_str(), window_.context()->validationEnabled() ? "on" : "off",
              stepper->name().c_str());
  std::fflush(stdout);
  hands_ = input_->at(t_);
  wands_ = hands_.wands;
  sim_ = startingSimulation(run_, *input_, wands_, std::move(stepper));
  if (const std::string bubble = bubbleInWords(run_, *sim_); !bubble.empty()) std::printf("live: %s\n", bubble.c_str());
  show_.frame(*sim_, sim_->stats(), "film_created");
  scriptCalibration_ = calibrationOf(run_.input);
  advisedAt_ = std::chrono::steady_clock::now() - std::chrono::seconds(10);
  lastReopen_ = std::chrono::steady_clock::now();
  threads_.emplace();
  start_ = std::chrono::steady_clock::now();
  pacer_.emplace(PacerOptions{run_.params.frameTime, sim_->solverSweeps(), o_.minSweeps, 4,
                              o_.fixedStep ? 1.0 : renderScaleFloor(floorScale_, image_.width, image_.height)},
                 start_);
  lastTitle_ = lastPresented_ = start_;
  return true;
}

bool LiveShow::frame() {
  WindowKeys keys = window_.poll();
  addScriptedKeys(o_.keys, shown_, keys);
  takeCues(keys);
  // Parameter sets and presets between frames (keys 1-9 recall presets); their reports go to the console and OSC.
  if (control_) {
    if (keys.preset > 0) control_->recallNumbered(keys.preset);
    control_->betweenFrames(*sim_, [this](const std::string& what) { reportControl(what); });
  }
  if (keys.quit || waiting_->quit() || InterruptCatcher::requested()) {  // Esc/Q, closed, a cue, Ctrl-C, SIGTERM
    if (fromCue_.quit) reportCue(shown_, true, CueAction::Quit, "the show ends", t_);
    return false;
  }
  act(keys);
  if (quitRequested_) return false;  // Esc or Ctrl-C while an input restarted waited for a performer
  int due = 0;
  double simMs = 0;
  if (paused_) {
    pacer_->resync();
  } else {
    due = o_.fixedStep ? 1 : pacer_->framesDue();
    if (due == 0) {  // ahead of the wall clock: wait for the next frame rather than draw the same one twice
      pacer_->sleepUntilDue();
      due = pacer_->framesDue();
    }
    sim_->setSolverSweeps(o_.fixedStep ? 0 : pacer_->sweeps());
    const auto simStart = std::chrono::steady_clock::now();
    // The frames due in steps of at most longestStep frames: a long step costs what a short one does, so a
    // machine that is behind halves its simulation work before the solver's sweeps go down.
    const int longest = run_.params.integrator != 0 ? o_.longestStep : 1;  // explicit: substeps would grow instead
    for (int done = 0; done < due && !quitRequested_;) {
      const int frames = std::min(longest, due - done);
      const auto stepStart = std::chrono::steady_clock::now();
      advanceStep(frames);
      overlap_.addStep(sim_->stepper(), steadySeconds(stepStart), steadySeconds(std::chrono::steady_clock::now()));
      done += frames;
    }
    simMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - simStart).count();
    if (quitRequested_) return false;  // Esc or Ctrl-C while an input restarted waited for a performer
  }
  present(keys, due, simMs);
  return ++shown_ != o_.frames;
}

// The keys and cues of this frame acted on.
void LiveShow::act(const WindowKeys& keys) {
  if (keys.fullscreen) {
    toggleFullscreen(shown_);
    if (fromCue_.fullscreen) show_.cue("fullscreen", window_.fullscreen() ? "full screen" : "a window", t_);
  }
  if (keys.performerView)
    reportCue(shown_, fromCue_.performerView, CueAction::PerformerView, performerView_.toggle(), t_);
  if (keys.operatorOverlay)
    reportCue(shown_, fromCue_.operatorOverlay, CueAction::Operator, toggleOperatorOverlay(), t_);
  if (keys.mirrorView) say(shown_, mirrorView_.toggle());
  if (keys.resetCamera) {
    camera_->home();
    reportCue(shown_, fromCue_.resetCamera, CueAction::Camera,
              run_.render.followCamera ? "the camera follows the film again" : "the scene's camera again", t_);
  }
  if (keys.pause) {
    paused_ = pauseCue_ >= 0 ? pauseCue_ == 1 : !paused_;
    reportCue(shown_, fromCue_.pause, CueAction::Pause, paused_ ? "paused" : "resumed", t_);
  }
  if (keys.reset) {
    restartInput();
    if (quitRequested_) return;
    inputStart_ = t_;
    loop_.restart();
    hands_ = input_->at(0);
    wands_ = hands_.wands;
  }
  // A performer's wands dip again by themselves once they are apart: a film dipped between closed tips would
  // only pinch off at once into a sliver. A script or a recording loops instead (PerformanceLoop).
  const bool wandsApart = run_.tool.kind == ToolKind::Ring ||
                          (wands_.rightPosition - wands_.leftPosition).norm() > 2.0f * run_.params.pinchDistance;
  const bool autoDip =
      performer_ && o_.autoDip >= 0 && filmGoneSince_ >= 0 && t_ - filmGoneSince_ >= o_.autoDip && wandsApart;
  if (keys.reset)
    reportCue(shown_, fromCue_.reset, CueAction::Reset,
              dipNewFilm("reset: new film, performance from its start", "film_created"), t_,
              "new film, performance from its start");
  else if (keys.dip)
    reportCue(shown_, fromCue_.dip, CueAction::Dip, dipNewFilm("dip: new film", "film_created"), t_, "new film");
  else if (autoDip)
    say(shown_, dipNewFilm("auto dip: new film", "film_created"));
  if (keys.burst) {
    const bool poked = pokeTop(*sim_);
    burstByCue_ = poked && fromCue_.burst;
    reportCue(shown_, fromCue_.burst, CueAction::Burst, poked ? "burst" : "B: no film to burst", t_,
              poked ? "burst" : "no film to burst");
  }
  if (keys.nextColouring) {
    renderer_->setColouring(static_cast<Colouring>((static_cast<int>(renderer_->options().colouring) + 1) % 3));
    reportCue(shown_, fromCue_.nextColouring, CueAction::Colouring, colouringName(renderer_->options().colouring), t_);
  }
}

// The wands of show time t: the input's, or on their way back to its start while the performance loops.
void LiveShow::moveWands() {
  switch (loop_.next(t_, performanceOver(), freeBubble_ || filmGoneSince_ >= 0, filmGoneSince_)) {
    case PerformanceLoop::Action::StartReturn: {
      restartInput();
      const WandState from = wands_;
      loop_.startReturn(t_, from, input_->at(0).wands);
      char text[120];
      std::snprintf(text, sizeof text, "the performance is over: the wands go back to its start (%.1f s)",
                    loop_.returnSeconds());
      say(shown_, text);
      wands_ = loop_.returnWands(t_);
      return;
    }
    case PerformanceLoop::Action::Return:
      wands_ = loop_.returnWands(t_);
      return;
    case PerformanceLoop::Action::DipAndPlay:
      wands_ = loop_.returnWands(t_);
      inputStart_ = t_;
      ++loops_;
      say(shown_, dipNewFilm("loop: new film, the performance from its start", "film_created"));
      return;
    case PerformanceLoop::Action::StartPlaying:
      inputStart_ = t_;
      ++loops_;
      say(shown_, "loop: the performance from its start");
      [[fallthrough]];
    case PerformanceLoop::Action::Play:
      break;
  }
  hands_ = input_->at(t_ - inputStart_);  // a camera's newest hands: never waited for (input.wallClock)
  wands_ = hands_.wands;
  for (const std::string& m : input_->takeMessages()) {  // e.g. a camera's hands lost or found
    std::fprintf(stderr, "%s\n", m.c_str());
    window_.showMessage(m);
  }
  tellPerformer();
  if (input_->ended() && !inputLost_ && !loop_.looping()) {
    inputLost_ = true;
    if (!performer_) {  // a recording or a file played to its end: it plays again once the stage is empty
      say(shown_,
          "the input has played to its end; the wands rest" +
              std::string(o_.autoDip >= 0 ? " until the stage is empty, then it plays again" : " (R plays it again)"));
      return;
    }
    // The wands rest where they are (wand_input.h) until the input returns.
    announce(
        "the input has ended or was lost; the wands rest" +
        std::string(run_.input.spec() == "kinect" ? ", and the camera is looked for again" : " (R starts it again)"));
    show_.frame(*sim_, sim_->stats(), "input_lost");
  }
}

// `frames` frames of h on the wall clock in one step (more than one when behind it): the input, then the
// simulation; a simulation that blows up is replaced.
void LiveShow::advanceStep(int frames) {
  t_ += static_cast<double>(run_.params.frameTime) * frames;
  moveWands();
  sendHands();
  if (inputLost_ && run_.input.spec() == "kinect" &&
      std::chrono::duration<double>(std::chrono::steady_clock::now() - lastReopen_).count() >= kReopenCameraEvery) {
    lastReopen_ = std::chrono::steady_clock::now();
    try {
      input_ = openInput();
      inputStart_ = t_;
      inputLost_ = false;
      announce("the camera is back");
      show_.frame(*sim_, sim_->stats(), "input_back");
    } catch (const HandSourceError&) {  // not yet: the wands go on resting
    }
  }
  try {
    sim_->setFrameTime(run_.params.frameTime * static_cast<float>(frames));
    threads_->update();
    givePerformerBody(*sim_, hands_);
    sim_->advanceFrame(wands_);
    const FrameStats stats = sim_->stats();
    std::string events = describeEvents(sim_->lastEvents());
    if (const auto poke = events.find("burst_by_poke"); burstByCue_ && poke != std::string::npos) {
      events.replace(poke, std::string("burst_by_poke").size(), "burst_by_cue");
      burstByCue_ = false;
    }
    if (const std::string touched = touchInWords(*sim_, events); !touched.empty()) say(shown_, touched);
    show_.frame(*sim_, stats, events);
    freeBubble_ = freeBubble_ || sim_->lastEvents().pinchedOff;
    if (stats.particles == 0 && filmGoneSince_ < 0) filmGoneSince_ = t_;
  } catch (const SimulationUnstable& e) {
    // The show goes on: the broken simulation is dropped whole (a dip keeps state the blow-up may have
    // poisoned, such as the air) and a new one starts with a film on the wands as they are.
    ++recoveries_;
    std::fprintf(stderr, "warning: %s\n", e.what());
    sim_ = std::make_unique<Simulation>(run_.params, run_.tool, wands_, newStepper());
    filmGoneSince_ = -1;
    freeBubble_ = false;
    ++dips_;
    announce("the simulation became unstable; a new film is dipped");
    show_.frame(*sim_, sim_->stats(), "simulation_unstable film_created");
  }
}

// The frame drawn (the window's blit scales the image to the window: dynamic resolution), streamed and counted.
// The device draws it while the next frame is simulated (a film on the Vulkan stepper's device is copied there
// first): the frame drawn last time is shown and streamed here first, and this one goes to the device.
void LiveShow::present(const WindowKeys& keys, int due, double simMs) {
  const auto renderStart = std::chrono::steady_clock::now();
  showDrawnFrame();
  const auto [width, height] = showSize();
  renderer_->resize(std::max(16, static_cast<int>(std::lround(width * pacer_->renderScale()))),
                    std::max(16, static_cast<int>(std::lround(height * pacer_->renderScale()))));
  const State& drawn = filmToDraw(*sim_, filmOnDevice_).state;  // where the particles are
  const OrbitCamera view = camera_->update(drawn, wands_, run_.params.frameTime * static_cast<float>(due),
                                           window_.camera(), keys.cameraMoved);
  if (filmGoneSince_ < 0) inPicture_.add(view, camera_->aspect(), drawn);
  updateInset();
  const WireFrame wire = sim_->wireFrame(wands_);
  DeviceFilm deviceFilm;
  RenderFrame frame = renderFrameOf(*sim_, wire, view, filmOnDevice_, deviceFilm);
  mirrorView_.apply(frame, input_ ? input_->cameraCalibration() : nullptr);
  window_.submit(*renderer_, frame);
  const auto now = std::chrono::steady_clock::now();
  pacer_->record(due, simMs, std::chrono::duration<double, std::milli>(now - renderStart).count());
  if (filmGoneSince_ < 0 && !paused_)
    filmShown_.add(due, sim_->solverSweeps(), std::chrono::duration<double>(now - lastPresented_).count(),
                   pacer_->renderScale());
  lastPresented_ = now;
  if (control_)
    control_->publish(*sim_, t_, paused_,
                      filmGoneSince_ >= 0 ? "none"
                      : freeBubble_       ? "free_bubble"
                                          : "on_wands",
                      performer_ ? (input_->performerFound() ? "found" : "waiting") : "none");
  if (now - lastTitle_ > std::chrono::seconds(1)) {  // the show's figures in the title bar, once a second
    window_.setTitle(liveFigures(*pacer_, shown_, start_, now));
    lastTitle_ = now;
  }
}

void LiveShow::showDrawnFrame() {
  if (!window_.showSubmitted()) return;
  overlap_.addRender(renderer_->takeDrawnIntervals());
  if (stream_) {
    stream_->offer(window_.captured());
    for (const std::string& m : stream_->takeMessages()) std::fprintf(stderr, "warning: %s\n", m.c_str());
  }
}

int LiveShow::finish() {
  showDrawnFrame();  // the last frame drawn
  const auto end = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(end - start_).count();
  const size_t errors = window_.context()->validationErrors();
  std::printf("live: %s, %ld frames simulated, %ld dropped\n", liveFigures(*pacer_, shown_, start_, end).c_str(),
              pacer_->simulatedFrames(), pacer_->droppedFrames());
  std::printf(
      "live: presented %ld frames in %.2f s (%.1f frames/s), %ld dips, %zu validation errors, %ld recoveries "
      "from instability\n",
      shown_, seconds, static_cast<double>(shown_) / std::max(seconds, 1e-9), dips_, errors, recoveries_);
  std::printf("live: %s\n", filmShown_.describe(run_.params.frameTime).c_str());
  // The device draws each frame while the next one is simulated (on the Vulkan backend from its copy of the film).
  std::printf("live: the step and the render overlapped %s\n", describeOverlap(overlap_.totals(), seconds).c_str());
  std::printf(
      "live: a film was on stage for %.1f%% of the show's wall time (%.1f of %.1f s); the performance "
      "played again %ld times\n",
      100.0 * filmShown_.wallSeconds / std::max(seconds, 1e-9), filmShown_.wallSeconds, seconds, loops_);
  if (inPicture_.frames > 0)
    std::printf("live: the film's centre was in the picture on %ld of the %ld frames it was on stage (%.1f%%)\n",
                inPicture_.inside, inPicture_.frames,
                100.0 * static_cast<double>(inPicture_.inside) / static_cast<double>(inPicture_.frames));
  if (cues_)
    std::printf("live: OSC cues: %ld taken, %ld unknown and %ld malformed ignored\n", cues_->taken(), cues_->unknown(),
                cues_->malformed());
  if (control_) std::printf("live: %s\n", control_->totals().c_str());
  if (stream_) {
    const long sent = stream_->sent();
    stream_.reset();  // ends ffmpeg: what it sent is counted
    std::printf("live: stream: %ld frames sent, %ld dropped\n", sent, shown_ - sent);
  }
  if (const Simulation::BudgetRecord& budget = sim_->energyBudgetRecord(); budget.frames > 0)
    std::printf(
        "live: the implicit step's energy budget took energy back on %ld steps (smallest factor on the "
        "wobble %.2f, most drift given back %.3f m/s; docs/model.md)\n",
        budget.frames, static_cast<double>(budget.smallestScale), static_cast<double>(budget.largestShift));
  return InterruptCatcher::exitStatus(errors == 0 ? 0 : 4);  // 130 or 143 after Ctrl-C or SIGTERM
}

}  // namespace gb
