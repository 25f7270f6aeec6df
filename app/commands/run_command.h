#pragma once
// `giantbubble run`: a headless simulation of a performance (scripted, recorded or live), written to an output
// folder.

#include <filesystem>
#include <string>

#include "app/commands/input_options.h"
#include "app/outputs/render_output.h"
#include "capture/scripted_gestures.h"
#include "host/backend.h"
#include "model/params.h"
#include "model/wire_frame.h"
#include "scene/run_options.h"

namespace gb {

// Runs the simulation and writes its outputs; prints progress and a summary. Returns the process exit code:
// 0 on success, 3 when the simulation became unstable (outputs up to the last good frame are kept), 5 when it
// finished but the video could not be written (every other output is), 128 + the signal (130 for Ctrl-C, 143
// for SIGTERM, 129 for SIGHUP) when a signal stopped it (the frame in flight finished, every output written, status
// "interrupted" in stats.json). An output that cannot be written throws OutputError naming it.
int runSimulation(const RunOptions& options);

}  // namespace gb
