#pragma once
// The live show of `giantbubble live`: a window, the wands on the chosen input, the film simulated on the wall clock
// and drawn each frame. Its parts are objects it owns: the window and its renderer, the OSC cues coming in
// (osc_cues.h) and the show's events going out (osc_events.h), the picture's stream (video_stream.h), the camera
// that follows the film (live_camera.h) and the performer view (performer_view.h). A show is set up (the input opened,
// a performer waited for, the first film dipped), runs frame by frame until it ends, and finishes with its totals.

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands/input_options.h"
#include "app/commands/interrupt.h"
#include "app/commands/run_command.h"
#include "app/commands/thread_policy.h"
#include "app/control/live_control.h"
#include "app/outputs/osc_events.h"
#include "app/outputs/step_render_overlap.h"
#include "app/show/live_camera.h"
#include "app/show/mirror_view.h"
#include "app/show/osc_cues.h"
#include "app/show/performance_loop.h"
#include "app/show/performer_view.h"
#include "app/show/realtime_pacer.h"
#include "app/show/video_stream.h"
#include "host/renderer.h"
#include "host/window.h"
#include "simulation/simulation.h"

namespace gb {

struct LiveOptions {
  RunOptions run;  // tool, input, parameters, OSC, backend (run.render.image: size and colouring)
  std::string tool = "two-wands";
  std::string backend = "auto";
  std::string betweenSteps = "auto";  // Vulkan: where the contacts, statistics and film checks run (run.betweenSteps)
  std::vector<std::string> assignments;  // --param NAME=VALUE
  double autoDip = 1.0;                  // seconds of empty stage before the wands dip again (negative: never)
  long frames = 0;                       // quit after this many presented frames (0: when the window closes)
  std::vector<std::string> keys;         // scripted key presses FRAME:KEY (keys r d b p c), as if typed at that frame
  bool fixedStep = false;        // one simulation frame per presented frame (slow motion when the machine is slow)
  int minSweeps = 3;             // the fewest solver sweeps the wall clock may leave the film (realtime_pacer.h)
  int longestStep = 2;           // frames of time one implicit step may cover when the machine falls behind
  double minRenderScale = 0.5;   // the smallest image drawn when behind, as a fraction of the window's size
  bool fullscreen = false;       // start full screen (borderless, the monitor's resolution)
  int monitor = 0;               // the monitor for full screen
  int oscIn = 0;                 // UDP port cues come in on (0: none)
  std::string stream;            // where ffmpeg sends the picture (empty: nowhere)
  bool operatorOverlay = false;  // start with the operator overlay on (O toggles it)
  ControlOptions control;        // --control: OSCQuery and the control page; presets (control/live_control.h)
};

// A scripted key press of --keys: at presented frame `frame`, key `key` (r d b p c f v o, and h for Home).
struct KeyPress {
  long frame = 0;
  char key = 0;
};
inline constexpr long kMaxKeyFrame = 100'000'000;  // as --frames
// FRAME:KEY, or nothing with `why` naming what is wrong (not FRAME:KEY, a frame too large).
std::optional<KeyPress> parseKeyPress(const std::string& text, std::string& why);

class PerformerWaitScreen;  // live_show.cpp

class LiveShow {
 public:
  // Opens the window (full screen if asked), the renderer, the cues and the stream.
  explicit LiveShow(LiveOptions options);
  ~LiveShow();
  LiveShow(const LiveShow&) = delete;  // owns the window and the device
  LiveShow& operator=(const LiveShow&) = delete;

  // Sets the show up, runs it until it ends (Esc/Q, the window closed, a cue, Ctrl-C, --frames) and finishes it.
  // Returns the exit code: 0, 4 when the Vulkan validation layer reported errors, 128 + the signal when Ctrl-C,
  // SIGTERM or SIGHUP ended the show.
  int run();

 private:
  // The set-up: the input opened (a camera waits for a performer, the window alive meanwhile), the stepper, the
  // first film. False when the show ended while it waited.
  bool setUp();
  // One presented frame: the keys and cues, the frames of simulation due on the wall clock, the picture. False when
  // the show ends.
  bool frame();
  // The show's totals on the console; the exit code.
  int finish();

  // The parts of a frame.
  void takeCues(WindowKeys& keys);
  void act(const WindowKeys& keys);
  void moveWands();
  void advanceStep(int frames);
  void present(const WindowKeys& keys, int due, double simMs);
  // Waits for the frame drawn last and shows it (Window::showSubmitted), streams it and counts its drawing.
  void showDrawnFrame();

  // What the show says and does on the way.
  void say(long frame, const std::string& what) const;
  void reportControl(const std::string& what);
  void announce(const std::string& what);
  void reportCue(long frame, bool cued, CueAction action, const std::string& keyText, double time,
                 const std::string& done = {});
  void toggleFullscreen(long frame);
  std::string toggleOperatorOverlay();
  void updateInset();
  bool serviceWhileWaiting();
  void tellWait(const std::string& message);
  std::unique_ptr<WandInput> openInput();
  void restartInput();
  std::string dipNewFilm(const std::string& why, const std::string& events);
  [[nodiscard]] bool performanceOver() const;
  void sendHands();
  void tellPerformer();
  [[nodiscard]] std::array<int, 2> showSize() const;
  [[nodiscard]] std::unique_ptr<Stepper> newStepper() const;

  LiveOptions o_;
  RunOptions& run_;
  ShowControl show_;
  std::unique_ptr<OscCueReceiver> cues_;
  std::unique_ptr<LiveControl> control_;  // parameters over OSC, presets, OSCQuery and the control page
  RenderOptions image_;
  Window window_;
  const std::array<int, 2> windowedSize_;  // the show's image in a window; full screen draws the monitor's size
  const InterruptCatcher interrupts_;      // Ctrl-C ends the show as Esc does, with its totals
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<VideoStream> stream_;
  std::unique_ptr<LiveCamera> camera_;
  PerformerView performerView_;
  MirrorView mirrorView_{run_.render.mirror, run_.render.mirrorRoom};
  std::optional<RealTimePacer> pacer_;  // made once the show starts
  double floorScale_;

  // The cues that came in, as the keys they stand for; `fromCue_` marks the ones a cue asked for, to report them.
  WindowKeys fromCue_;
  int pauseCue_ = -1;  // /pause with an argument: 1 pause, 0 resume
  bool viewTold_ = false;
  long waitFrames_ = 0;
  std::unique_ptr<PerformerWaitScreen> waiting_;

  std::unique_ptr<WandInput> input_;
  bool filmOnDevice_ = false;
  double t_ = 0;
  WandFrame hands_;
  WandState wands_;
  std::unique_ptr<Simulation> sim_;

  bool paused_ = false, quitRequested_ = false;
  long shown_ = 0, dips_ = 0, recoveries_ = 0, loops_ = 0;
  double filmGoneSince_ = -1;  // time the last film disappeared, -1 while there is one
  double inputStart_ = 0;      // show time at which the current input's time 0 is
  bool inputLost_ = false;
  bool freeBubble_ = false;  // the film on stage has pinched off: the wands hold none
  bool burstByCue_ = false;  // the poke of a cue: its burst is told as burst_by_cue
  // A script or a recording plays again once the stage is empty (performance_loop.h); a performer (a camera, the
  // mouse) dips again by themselves.
  const bool performer_;
  PerformanceLoop loop_;
  const double scriptEnd_;
  Calibration scriptCalibration_;  // the hands of a script as OSC joints
  // The performer's state over OSC as it changes, and the advice on the console as it changes (at most every 2 s).
  std::array<bool, 2> handsLost_{false, false};
  std::string advised_;
  std::chrono::steady_clock::time_point advisedAt_;
  std::chrono::steady_clock::time_point lastReopen_;
  StepRenderOverlap overlap_;  // the step's time and the device's drawing (app/outputs/step_render_overlap.h)
  std::optional<SimulationThreads> threads_;  // one fewer for each core another process keeps busy (thread_policy.h)
  std::chrono::steady_clock::time_point start_, lastTitle_, lastPresented_;

  // The show's figures while a film is on the wands or in the air. An empty stage after a burst draws and keeps time
  // easily: figures over the whole show would hide how it runs while there is something to see.
  struct FilmShownTally {
    long presented = 0, simulated = 0, sweeps = 0;
    double wallSeconds = 0;
    long drawnSmaller = 0;     // frames drawn smaller than the window (dynamic resolution)
    double smallestScale = 1;  // the smallest of them, as a fraction of the window's width and height
    void add(int frames, int sweepsTaken, double seconds, double renderScale);
    [[nodiscard]] std::string describe(double frameTime) const;
  } filmShown_;
  // How often the film was in the picture while it was on stage: its centre inside the image.
  struct InPictureTally {
    long frames = 0, inside = 0;
    void add(const OrbitCamera& camera, float aspect, const State& film);
  } inPicture_;
};

}  // namespace gb
