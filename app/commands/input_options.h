#pragma once
// The hand-input options shared by `giantbubble run` and `giantbubble record`: where the hands come from
// (--input, or the older --gesture NAME for script:NAME), the stabilizer, the calibration and the depth band.

#include <CLI/CLI.hpp>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "capture/hand_sources.h"
#include "capture/stabilizer.h"
#include "capture/wand_input.h"
#include "scene/run_options.h"

namespace gb {

// Adds --input, --gesture, --stabilizer, --performer, --reach, --camera-pitch, --depth-band and --mirrored.
void addInputOptions(CLI::App* command, InputOptions& options);
// Adds --bubble-at X,Y,Z and --bubble-radius R: a still free bubble placed in camera space (run and live; the film
// they start with is made by startingSimulation, app/show/performer_touch.h).
void addBubbleOptions(CLI::App* command, InputOptions& options);
// Adds --depth-band NEAR FAR (m) alone, as evaluate takes it.
void addDepthBandOption(CLI::App* command, std::vector<double>& band);

bool isCamera(const std::string& spec);                  // kinect or fakenect:DIR: hands found in depth
Calibration calibrationOf(const InputOptions& options);  // throws std::invalid_argument on a bad --performer
SourceOptions sourceOptionsOf(const InputOptions& options, const GestureOptions& gesture);
StabilizerOptions stabilizerOptionsOf(const InputOptions& options);

// What moves the wands of a run: a script exactly as written (world space, no stabilizer), any other input
// through the stabilizer and the calibration. Camera inputs and trajectories wait for a performer (both hands
// seen); `waiting` says where the wait's messages go and what ends it early (its `enabled` is decided here; by
// default the messages go to stderr and Ctrl-C ends the wait). Throws HandSourceError when the input cannot be
// opened. `wrap`, when given, is handed the hand source of an input that is not a script and returns the one the
// wands follow (the live window keeps a camera's depth frames for its performer view). A camera (kinect,
// fakenect:DIR) is read on a thread of its own (ThreadedHandSource): its hands are found beside the frame loop.
using HandSourceWrapper = std::function<std::unique_ptr<HandSource>(std::unique_ptr<HandSource>)>;
std::unique_ptr<WandInput> makeWandInput(const InputOptions& options, const GestureOptions& gesture,
                                         PerformerWait waiting = {}, const HandSourceWrapper& wrap = {});

}  // namespace gb
