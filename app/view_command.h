#pragma once
// `giantbubble view`: the live window. A scripted performance plays in a window with the rendered film; the
// mouse orbits (drag) and zooms (wheel); keys: R reset, D dip the wands (new film), B burst, Space/P pause,
// C next colouring (interference, thickness, air flow), Home camera back, Esc/Q quit.

#include <string>
#include <vector>

#include "render_output.h"
#include "run_command.h"

namespace CLI {
class App;
}

namespace gb {

struct ViewOptions {
  RunOptions run;                  // tool, gesture, parameters, backend (run.render.image: size and colouring)
  std::string tool = "two-wands";
  std::string gesture = "straight";
  std::string backend = "auto";
  long frames = 0;                 // quit after this many presented frames (0: when the window closes)
  std::vector<std::string> keys;   // scripted key presses FRAME:KEY (keys r d b p c), as if typed at that frame
};

// Adds the `view` subcommand and its options to the application.
CLI::App* addViewCommand(CLI::App& app, ViewOptions& options);

// Runs the window until it is closed (or options.frames are shown). Returns the exit code: 0, 1 on an error (the
// message printed), 4 when the Vulkan validation layer reported errors.
int runView(ViewOptions options);

}  // namespace gb
