#pragma once
// Ctrl-C (SIGINT) and SIGTERM end a run cleanly instead of killing it: while an InterruptCatcher
// lives, the first signal only sets a flag that the run loop reads between frames, so the frame in flight
// finishes, stats.json is written with status "interrupted" and the video is closed playable. The handler is
// one-shot: a second Ctrl-C kills the program at once, for a run that hangs.

namespace gb {

class InterruptCatcher {
 public:
  InterruptCatcher();                                  // catches SIGINT and SIGTERM
  ~InterruptCatcher();                                 // restores what was there before
  InterruptCatcher(const InterruptCatcher&) = delete;  // owns the process's signal dispositions
  InterruptCatcher& operator=(const InterruptCatcher&) = delete;
  // The signal that asked to stop, or 0.
  [[nodiscard]] static int signal();
  [[nodiscard]] static bool requested() { return signal() != 0; }
};

// "interrupted (SIGINT)" and the like, for messages.
const char* signalName(int signal);

}  // namespace gb
