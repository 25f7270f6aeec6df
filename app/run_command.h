#pragma once
// `giantbubble run`: a headless simulation of a performance (scripted, recorded or live), written to an output
// folder.

#include <filesystem>
#include <string>

#include "backend.h"
#include "input_options.h"
#include "params.h"
#include "render_output.h"
#include "scripted_gestures.h"
#include "wire_frame.h"

namespace gb {

struct RunOptions {
  std::string scene = "default";  // the scene's name, for stats.json and the summary
  Params params;
  WandTool tool;
  InputOptions input;  // what moves the wands (default: the straight scripted gesture)
  GestureOptions gestureOptions;
  double duration = 4.0;           // simulated seconds
  bool durationFromInput = false;  // a recorded input runs for its own length instead
  double burstAt = 3.5;            // poke the top of the film at this time (s); negative: never
  bool burstOnAnyInput = false;    // poke whatever the input; otherwise only a scripted input is poked
                                   // (set by --burst-at, or a scene file with its own non-script input)
  std::filesystem::path outDir = "out";
  int plyEvery = 25;    // write a mesh every this many frames (0: never)
  int imageEvery = 10;  // write a thickness image every this many frames (0: never)
  bool progress = true;
  bool realtime = false;  // keep the wall clock: wait when ahead, fewer solver sweeps when behind
  Backend backend = Backend::Auto;
  std::string device;                             // Vulkan device index or name part (empty: best available)
  WorkPlace betweenSteps = WorkPlace::Automatic;  // Vulkan: where the contacts, statistics and film checks run
  std::string osc;                                // HOST:PORT to send events and the bubble's state to (empty: off)
  bool renderIfPossible = false;                  // the main job renders when it can and says so when it cannot
  std::string experiment;                         // a physics experiment instead of a performance (experiments.h)
  RenderOutputOptions render;                     // --render: rendered frames and video (app/render_output.h)
};

// The longest run a duration taken from a recorded input may ask for, as --duration allows (s).
inline constexpr double kMaxRunSeconds = 3600.0;
// The earliest --burst-at (and a scene's burst_at): any negative time is never.
inline constexpr double kNeverBurst = -1e9;

// Runs the simulation and writes its outputs; prints progress and a summary. Returns the process exit code:
// 0 on success, 3 when the simulation became unstable (outputs up to the last good frame are kept), 5 when it
// finished but the video could not be written (every other output is), 128 + the signal (130 for Ctrl-C, 143
// for SIGTERM, 129 for SIGHUP) when a signal stopped it (the frame in flight finished, every output written, status
// "interrupted" in stats.json). An output that cannot be written throws OutputError naming it.
int runSimulation(const RunOptions& options);

}  // namespace gb
