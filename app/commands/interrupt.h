#pragma once
// Ctrl-C (SIGINT), SIGTERM and SIGHUP (the terminal closed) end a run cleanly instead of killing it: while an
// InterruptCatcher lives, the first signal only sets a flag that the run loop reads between frames, so the frame in
// flight finishes, stats.json is written with status "interrupted" and the video is closed playable; the command
// then exits 128 + the signal (130, 143, 129). The handler is one-shot: a second Ctrl-C kills the program at once,
// for a run that hangs. Signals restart what they interrupt (SA_RESTART), so nothing waits on a file that could
// block: inputs are opened without blocking (untrusted.h).

namespace gb {

class InterruptCatcher {
 public:
  InterruptCatcher();                                  // catches SIGINT, SIGTERM and SIGHUP
  ~InterruptCatcher();                                 // restores what was there before
  InterruptCatcher(const InterruptCatcher&) = delete;  // owns the process's signal dispositions
  InterruptCatcher& operator=(const InterruptCatcher&) = delete;
  // The signal that asked to stop, or 0.
  [[nodiscard]] static int signal();
  [[nodiscard]] static bool requested() { return signal() != 0; }
  // The exit status of a command that ends now: 128 + the signal that asked to stop, else `otherwise`.
  [[nodiscard]] static int exitStatus(int otherwise) { return requested() ? 128 + signal() : otherwise; }
};

// "SIGINT", "SIGTERM", "SIGHUP", for messages.
const char* signalName(int signal);

}  // namespace gb
