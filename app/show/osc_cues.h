#pragma once
// Show control in (giantbubble live --osc-in PORT): an operator's cue software (QLab, TouchDesigner, a phone running
// an OSC controller) drives the show with the keys' actions as OSC messages over UDP (liblo):
//
//   /giantbubble/dip            D      dip the wands: a new film
//   /giantbubble/burst          B      burst the film (the event burst_by_cue)
//   /giantbubble/reset          R      the input and the film from the start
//   /giantbubble/pause          Space  pause or resume; with an argument, 1 pauses and 0 resumes (a toggle button)
//   /giantbubble/colouring      C      the next colouring
//   /giantbubble/camera         Home   the camera back to following the film
//   /giantbubble/fullscreen     F      full screen or a window
//   /giantbubble/performer_view V      the performer view on or off
//   /giantbubble/operator       O      the operator overlay on or off
//   /giantbubble/quit           Esc    end the show
//
// A cue takes no argument, or one number: a controller's push button sends 1 when pressed and 0 when let go, and
// the 0 is no cue (except for /pause, where it resumes). Anything else is counted and ignored, never fatal: a
// message to another address (unknown), one with other arguments or a packet that is not OSC (malformed). The
// receiver is polled by the show's loop between frames; it never waits. docs/formats.md describes the messages.

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace gb {

enum class CueAction { Dip, Burst, Reset, Pause, Colouring, Camera, Fullscreen, PerformerView, Operator, Quit };

struct Cue {
  CueAction action = CueAction::Dip;
  int state = -1;  // /pause: 1 pause, 0 resume, -1 toggle
};

// The cue's name as in its address and in reports ("dip", "performer_view").
const char* cueName(CueAction action);

class OscCueReceiver {
 public:
  // Listens on UDP `port` (all IPv4 interfaces; 0: a free port, port() says which). Throws std::runtime_error
  // naming the port when it cannot.
  explicit OscCueReceiver(int port);
  ~OscCueReceiver();
  OscCueReceiver(const OscCueReceiver&) = delete;  // owns the socket
  OscCueReceiver& operator=(const OscCueReceiver&) = delete;

  // The cues that arrived since the last call, in order; at most kMostPerPoll messages are read, so a flood cannot
  // stall the show (the rest wait for the next call).
  std::vector<Cue> poll();
  static constexpr int kMostPerPoll = 64;

  // Messages to addresses that are no cue go to `other` first (live's parameters and presets, control/live_control.h):
  // it gets the address and the liblo message (a lo_message) and returns false for an address it does not take.
  using OtherMessages = std::function<bool(const char* path, void* message)>;
  void setOtherMessages(OtherMessages other) { other_ = std::move(other); }

  [[nodiscard]] int port() const;
  [[nodiscard]] long taken() const { return taken_; }
  [[nodiscard]] long unknown() const { return unknown_; }
  [[nodiscard]] long malformed() const { return malformed_; }
  // A line on each of the first few messages ignored ("osc in: unknown address /x (ignored)"), since the last call.
  std::vector<std::string> takeMessages();
  static constexpr long kMostReported = 5;

 private:
  struct Server;
  std::unique_ptr<Server> server_;
  std::vector<Cue> arrived_;
  std::vector<std::string> messages_;
  OtherMessages other_;
  long taken_ = 0, unknown_ = 0, malformed_ = 0;
  void ignore(bool unknown, const std::string& why);

  friend struct OscCueDispatch;
};

}  // namespace gb
