#pragma once
// Show control beyond the cues, for `giantbubble live`: every parameter over OSC (/giantbubble/param/NAME: with a
// number it is set, with none its value is sent back to the sender), presets (/giantbubble/preset NAME recalls,
// /giantbubble/preset/save NAME saves), and with --control PORT the OSCQuery server and the control page
// (control_server.h). The frame loop calls betweenFrames once a frame, beforeDip before a dip and publish after
// a frame is presented; nothing here ever waits on a client.

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/control/control_state.h"
#include "app/control/live_params.h"
#include "app/control/presets.h"

namespace CLI {
class App;
}

namespace gb {

class ControlServer;
class OscCueReceiver;
class Simulation;

struct ControlOptions {
  int port = -1;                    // --control: the OSCQuery server's TCP port (-1: none; 0: any free port)
  std::string bind = "127.0.0.1";   // --control-bind
  std::string token;                // --control-token: needed on every request when set
  std::string presets = "presets";  // --presets: the folder of preset files
};

// --control, --control-bind, --control-token, --presets.
void addControlOptions(CLI::App& command, ControlOptions& options);

class LiveControl {
 public:
  // A line for the console and OSC out: a set taken or refused, a preset recalled or saved.
  using Report = std::function<void(const std::string& what)>;

  // `wanted` is the show's parameter block; the receiver's other messages come here from now on. Throws
  // std::runtime_error naming the problem when the server cannot start.
  LiveControl(const ControlOptions& options, Params& wanted, OscCueReceiver& receiver);
  ~LiveControl();
  LiveControl(const LiveControl&) = delete;
  LiveControl& operator=(const LiveControl&) = delete;

  // Where the server is, for the console ("" without one).
  [[nodiscard]] std::string describe() const;
  // The sets and presets that arrived, reported and applied to the simulation.
  void betweenFrames(Simulation& sim, const Report& report);
  // The parameters waiting for a new film, into the simulation before it dips one.
  void beforeDip(Simulation& sim, const Report& report);
  // The show's status after a frame (showTime: the simulation's clock, s).
  void publish(Simulation& sim, double showTime, bool paused, const std::string& filmState,
               const std::string& performer);
  void lastEvent(const std::string& line);
  // Recalls the n-th saved preset in the order of their names (the keys 1-9), at the next betweenFrames.
  void recallNumbered(int n);
  // The totals at the end of the show.
  [[nodiscard]] std::string totals() const;

  // Reports per frame before the rest are only counted: a flood of sets must not flood the console.
  static constexpr int kMostReportsPerFrame = 4;

 private:
  ControlState state_;
  LiveParams params_;
  PresetLibrary presets_;
  std::unique_ptr<ControlServer> server_;
  std::string bind_;
  std::vector<std::string> reports_, recalls_, saves_;
  ShowStatus status_;
  std::chrono::steady_clock::time_point windowStart_ = std::chrono::steady_clock::now();
  long windowFrames_ = 0;
  long frames_ = 0;
  double frameThreadSeconds_ = 0;  // spent in betweenFrames and publish: the control's cost to the frame loop
  double windowShowTime_ = -1;

  bool onOsc(const char* path, void* message);
  void recall(const std::string& name);
  void save(const std::string& name);
  void flush(const Report& report);
};

}  // namespace gb
