#pragma once
// `giantbubble live` (also `view`): the live performance (LiveShow, live_show.h). The wands follow the chosen input (a
// Kinect, a fakenect recording, a trajectory file, a script, or the mouse: left and right buttons drag the hands, the
// wheel with a button held pushes them, the middle button orbits) and the film is rendered in a window; the mouse
// orbits (drag) and zooms (wheel); keys: R reset, D dip the wands (new film), B burst, Space/P pause, C next colouring
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

#include "app/show/live_show.h"

namespace CLI {
class App;
}

namespace gb {

// Adds the `live` subcommand (alias `view`) and its options to the application.
CLI::App* addLiveCommand(CLI::App& app, LiveOptions& options);

// Runs the show until the window is closed (or options.frames are shown). Returns the exit code: 0, 1 on an error
// (the message printed), 4 when the Vulkan validation layer reported errors, 128 + the signal when Ctrl-C, SIGTERM or
// SIGHUP ended the show.
int runLive(LiveOptions options);

}  // namespace gb
