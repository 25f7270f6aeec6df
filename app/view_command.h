#pragma once
// `giantbubble live` (also `view`): the live performance. The wands follow the chosen input (a Kinect, a fakenect
// recording, a trajectory file, a script, or the mouse: left and right buttons drag the hands, the wheel with a
// button held pushes them, the middle button orbits) and the film is rendered in a window; the mouse orbits (drag) and
// zooms (wheel); keys: R reset, D dip the wands (new film), B burst, Space/P pause, C next colouring
// (interference, thickness, air flow), F full screen, V performer view, Home camera back, Esc/Q quit. The camera
// follows the film (live_camera.h) until the mouse moves it. When the film is gone (burst, or a free bubble burst),
// a script or a recording plays again from its start (performance_loop.h) and a performer's wands dip again after
// --auto-dip seconds, so a show runs for hours with nobody at the keyboard. Events, the bubble's state and the hands
// go out as OSC with --osc; cues come in with --osc-in (osc_cues.h); the picture goes out with --stream
// (video_stream.h).
//
// A show never ends on its own: an unstable simulation is reported (console, OSC event
// simulation_unstable) and a new film dipped at once; an input that ends or is lost leaves the wands at rest
// (OSC input_lost) and a Kinect is looked for again every 2 s (input_back); only Esc/Q, the window closing or
// --frames end it.

#include <optional>
#include <string>
#include <vector>

#include "control/live_control.h"
#include "render_output.h"
#include "run_command.h"

namespace CLI {
class App;
}

namespace gb {

struct ViewOptions {
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

// A scripted key press of --keys: at presented frame `frame`, key `key` (r d b p c f v o, h for Home, 1-9 a preset).
struct KeyPress {
  long frame = 0;
  char key = 0;
};
inline constexpr long kMaxKeyFrame = 100'000'000;  // as --frames
// FRAME:KEY, or nothing with `why` naming what is wrong (not FRAME:KEY, a frame too large).
std::optional<KeyPress> parseKeyPress(const std::string& text, std::string& why);

// Adds the `view` subcommand and its options to the application.
CLI::App* addViewCommand(CLI::App& app, ViewOptions& options);

// Runs the window until it is closed (or options.frames are shown). Returns the exit code: 0, 1 on an error (the
// message printed), 4 when the Vulkan validation layer reported errors, 128 + the signal when Ctrl-C, SIGTERM or
// SIGHUP ended the show.
int runView(ViewOptions options);

}  // namespace gb
