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
  std::filesystem::path outDir = "out";
  int plyEvery = 25;    // write a mesh every this many frames (0: never)
  int imageEvery = 10;  // write a thickness image every this many frames (0: never)
  bool progress = true;
  bool realtime = false;  // keep the wall clock: wait when ahead, fewer solver sweeps when behind
  Backend backend = Backend::Auto;
  std::string device;             // Vulkan device index or name part (empty: best available)
  std::string osc;                // HOST:PORT to send events and the bubble's state to (empty: off)
  bool renderIfPossible = false;  // the main job renders when it can and says so when it cannot
  std::string experiment;         // a physics experiment instead of a performance (experiments.h)
  RenderOutputOptions render;     // --render: rendered frames and video (app/render_output.h)
};

// Runs the simulation and writes its outputs; prints progress and a summary. Returns the process exit code:
// 0 on success, 3 when the simulation became unstable (outputs up to the last good frame are kept).
int runSimulation(const RunOptions& options);

}  // namespace gb
