#pragma once
// `giantbubble run`: a headless simulation of a performance (scripted, recorded or live), written to an output
// folder.

#include <filesystem>
#include <string>
#include <vector>

#include "app/commands/input_options.h"
#include "app/outputs/render_output.h"
#include "capture/scripted_gestures.h"
#include "host/backend.h"
#include "model/params.h"
#include "model/wire_frame.h"
#include "scene/run_options.h"

namespace CLI {
class App;
}

namespace gb {

// The run command's line: the options, and the names some of them take until the line is parsed
// (resolveRunCommandLine turns those into options).
struct RunCommandLine {
  RunOptions options;                    // the scene's, which the command line changes
  std::string scene;                     // --scene: read before the other options, the base they change
  std::string tool;                      // --tool: two-wands or ring
  std::string backend = "auto";          // --backend
  std::string betweenSteps = "auto";     // --between-steps
  std::vector<std::string> assignments;  // --param NAME=VALUE, applied by the caller
};

// Adds the `run` subcommand and its options to the application.
CLI::App* addRunCommand(CLI::App& app, RunCommandLine& line);

// The names of a parsed line turned into options: the tool, the backend, where the work between steps runs, and
// what the command line leaves to the input or the scene (the duration, the poke, the scene's own video).
void resolveRunCommandLine(RunCommandLine& line, const CLI::App& command);

// Runs the simulation and writes its outputs; prints progress and a summary. Returns the process exit code:
// 0 on success, 3 when the simulation became unstable (outputs up to the last good frame are kept), 5 when it
// finished but the video could not be written (every other output is), 128 + the signal (130 for Ctrl-C, 143
// for SIGTERM, 129 for SIGHUP) when a signal stopped it (the frame in flight finished, every output written, status
// "interrupted" in stats.json). An output that cannot be written throws OutputError naming it.
int runSimulation(const RunOptions& options);

}  // namespace gb
