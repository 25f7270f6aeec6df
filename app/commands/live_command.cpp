#include "app/commands/live_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "app/commands/cli_checks.h"
#include "app/commands/input_options.h"
#include "app/outputs/render_output.h"
#include "app/show/video_stream.h"

namespace gb {

CLI::App* addLiveCommand(CLI::App& app, LiveOptions& o) {
  CLI::App* cmd =
      app.add_subcommand("live",
                         "perform live in a window: the wands follow --input (mouse: orbit, zoom; "
                         "keys: R reset, D dip, B burst, Space pause, C colouring, F full screen, V "
                         "performer view, M mirror view, O operator overlay, Home camera, 1-9 presets, Esc quit)");
  cmd->alias("view");
  // --input also takes "mouse" here: the left and right buttons drag the hands, the wheel pushes them.
  cmd->add_option("--scene", o.run.scene, "a built-in scene or a scene file (.toml); the other options change it")
      ->check(NotEmpty());
  cmd->add_option("--tool", o.tool, "bubble tool")->check(CLI::IsMember({"two-wands", "ring"}));
  addInputOptions(cmd, o.run.input);  // --input kinect|fakenect:DIR|trajectory:FILE|script:NAME, --gesture, ...
  addBubbleOptions(cmd, o.run.input);
  cmd->add_option("--param", o.assignments, "set a model parameter, NAME=VALUE (repeatable)");
  cmd->add_option("--osc", o.run.osc,
                  "send events, the bubble's size and position and the hands as OSC to HOST:PORT (UDP)")
      ->check(NotEmpty());
  cmd->add_option("--osc-in", o.oscIn,
                  "take cues as OSC on this UDP port: /giantbubble/dip, burst, reset, pause, colouring, camera, "
                  "fullscreen, performer_view, operator, quit")
      ->transform(WholeNumber(1, 65535));
  cmd->add_flag("--fullscreen", o.fullscreen, "full screen (borderless, at the monitor's resolution); F toggles");
  cmd->add_flag("--operator", o.operatorOverlay,
                "start with the operator overlay on: the show's messages over the window (never in the stream); O "
                "toggles it");
  cmd->add_option("--monitor", o.monitor, "the monitor for full screen, from 0 (the primary)")
      ->transform(WholeNumber(0, 63));
  cmd->add_option("--stream", o.stream,
                  "send the picture through ffmpeg to udp://HOST:PORT, srt://HOST:PORT, tcp://HOST:PORT (MPEG-TS), "
                  "rtmp://HOST/APP/KEY or a v4l2 device /dev/videoN")
      ->check([](const std::string& url) {
        try {
          (void)streamArguments(url, 16, 16);
          return std::string();
        } catch (const std::invalid_argument& e) {
          std::string why = e.what();  // "--stream 'URL': ...": CLI11 names the option itself
          return why.rfind("--stream ", 0) == 0 ? why.substr(9) : why;
        }
      });
  cmd->add_option("--auto-dip", o.autoDip, "seconds without a film before the wands dip again (negative: never)")
      ->check(FiniteRange(-1e9, 86400.0));
  cmd->add_option("--particles", o.run.params.particlesAtFullSolution, "particles of a film at full solution")
      ->transform(WholeNumber(16, kMaxParticles));
  cmd->add_option("--solution", o.run.params.solution, "remaining soap solution (0, 1]")->check(FiniteRange(0.01, 1.0));
  cmd->add_option("--backend", o.backend, "cpu, vulkan (on the window's device), or auto (Vulkan on a GPU)")
      ->check(CLI::IsMember({"cpu", "vulkan", "auto"}));
  cmd->add_option("--device", o.run.device, "Vulkan device: index or part of its name");
  cmd->add_option("--between-steps", o.betweenSteps,
                  "Vulkan backend: where the contact search, the statistics and the film checks run: device, cpu, or "
                  "auto (the device unless it is a CPU driver)")
      ->check(CLI::IsMember({"auto", "device", "cpu"}));
  cmd->add_option("--frames", o.frames, "quit after this many frames (0: when the window closes)")
      ->transform(WholeNumber(0, 100000000));
  cmd->add_option("--keys", o.keys,
                  "scripted key presses FRAME:KEY, e.g. 50:b 80:c (keys r d b p c f v o, h for Home, 1-9 a preset; "
                  "for tests and demos)")
      ->check([](const std::string& s) {
        std::string why;
        return parseKeyPress(s, why) ? std::string() : why;
      });
  cmd->add_flag("--fixed-step", o.fixedStep,
                "advance one 0.02 s frame per presented frame instead of keeping the wall clock (slow motion on a slow "
                "machine)");
  cmd->add_option("--min-render-scale", o.minRenderScale,
                  "smallest image drawn when the machine cannot keep up, as a fraction of the window's width and "
                  "height (scaled up to the window; 1: always the window's size)")
      ->check(FiniteRange(0.1, 1.0));
  cmd->add_option("--min-sweeps", o.minSweeps, "fewest solver sweeps per frame when the machine cannot keep up")
      ->transform(WholeNumber(1, 1000));
  cmd->add_option(
         "--longest-step", o.longestStep,
         "frames of time one implicit step may cover when the machine cannot keep up (1: every step one frame)")
      ->transform(WholeNumber(1, 5));
  addControlOptions(*cmd, o.control);  // --control, --control-bind, --control-token, --presets
  addRenderOptions(*cmd, o.run.render, RenderedFiles::None);
  return cmd;
}

int runLive(LiveOptions options) try {
  LiveShow show(std::move(options));
  return show.run();
} catch (const std::exception& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 1;
}

}  // namespace gb
