#pragma once
// What a run is asked to do: the options `giantbubble run` and `live` take from the command line and a scene file
// (scene_file.h) sets. Data only: app/ adds them to the commands (input_options.h, render_output.h) and runs them
// (run_command.h).

#include <array>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "capture/scripted_gestures.h"
#include "host/backend.h"
#include "host/renderer.h"
#include "model/params.h"
#include "model/wire_frame.h"

namespace gb {

// Where the hands come from (--input, or the older --gesture NAME for script:NAME), the stabilizer, the calibration
// and the depth band: shared by `giantbubble run` and `giantbubble record`.
struct InputOptions {
  std::string input;                           // kinect, fakenect:DIR, trajectory:FILE or script:NAME
  std::string gesture;                         // --gesture NAME, kept as an alias of --input script:NAME
  std::string stabilizer = "one-euro";         // one-euro (the default: less lag, docs/capture.md) or bspline (the
                                               //   paper)
  std::string performer;                       // X,Y,Z (m) between the resting hands, or auto; empty: auto for
                                               //   camera inputs (kinect, fakenect:DIR), 0,0,2 for the others
  double reach = 2.0;                          // world metres per metre of hand motion
  double cameraPitch = 0.0;                    // degrees the camera is tilted up
  std::vector<double> depthBand = {0.5, 4.0};  // metres: the performer stands inside this band
  bool mirrored = false;                       // the depth image is mirrored
  double runSeconds = std::numeric_limits<double>::infinity();  // how long the run lasts once the performer is
                                                                //   found: a trajectory file is read no further
  std::optional<std::array<double, 3>> bubbleAt;  // --bubble-at: a still free bubble's centre in camera space (m)
  double bubbleRadius = 0.15;                     // --bubble-radius: its radius in camera space (m)
  bool wallClock = false;  // the frame loop keeps the wall clock (live, run --realtime): a camera's newest hands are
                           //   used as they arrive, never waited for (StabilizedWands::followWallClock)

  [[nodiscard]] std::string spec() const;  // script:GESTURE, else --input, else script:straight
  [[nodiscard]] bool scripted() const { return spec().rfind("script:", 0) == 0; }
};

// Rendered pictures of a run (app/outputs/render_output.h writes them).
// The smallest drawn scale `run --render-scale` takes: below it the string and the wands are under a pixel wide.
inline constexpr float kSmallestDrawnScale = 0.25f;

struct RenderOutputOptions {
  bool enabled = false;               // --render (or the scene's [render] enabled), --no-render
  RenderOptions image;                // size and colouring (host/renderer.h)
  int samples = 0;                    // --samples: MSAA samples per pixel; 0: the command's own choice (samplesFor)
  float drawnScale = 0;               // --render-scale: `run` draws at this fraction of the image's size and scales
                                      // up to it; 0: the command's own choice (drawnScaleFor)
  int pngEvery = 1;                   // write render_NNNNN.png every N frames (0: none)
  std::string video = "render.mp4";   // in the output folder; empty: none. Needs ffmpeg
  double videoFps = 0;                // --video-fps: the video's frames per second, a whole fraction of the
                                      // simulation's; 0: the command's own choice (videoStrideFor)
  std::filesystem::path environment;  // equirectangular PNG the film reflects; empty: the built-in sky
  OrbitCamera camera;                 // its direction; with followCamera its target and distance frame the film
  bool followCamera = true;           // --camera follow (default): keep the film framed; fixed: `camera` as is
  bool mirror = false;                // --view mirror: from the depth camera, mirrored, the performer drawn in
                                      // (app/show/mirror_view.h); stage (default): the virtual stage from `camera`
  bool mirrorRoom = false;            // --mirror-room: the mirror view shows the room the camera sees behind the
                                      // performer instead of the virtual stage
};

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
  RenderOutputOptions render;                     // --render: rendered frames and video (app/outputs/render_output.h)
};

// The longest run a duration taken from a recorded input may ask for, as --duration allows (s).
inline constexpr double kMaxRunSeconds = 3600.0;
// The earliest --burst-at (and a scene's burst_at): any negative time is never.
inline constexpr double kNeverBurst = -1e9;

}  // namespace gb
