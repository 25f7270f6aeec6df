#pragma once
// What the frame loop shows the control server (control_server.h), which runs on its own thread: the parameters
// as set (those waiting for the next film included), the show's status and the presets. The frame loop publishes
// once a frame; the server reads a copy under the lock and never holds it while it talks to a client.

#include <mutex>
#include <string>
#include <vector>

#include "model/params.h"

namespace gb {

// The show's read-only status nodes (/giantbubble/status/...).
struct ShowStatus {
  double framesPerSecond = 0;      // presented, over the last second
  double realTimeFactor = 0;       // simulated seconds per wall second, over the last second
  double filmArea = 0;             // m^2
  std::string filmState = "none";  // on_wands, free_bubble, none
  std::string performer = "none";  // found, waiting, none (no camera)
  std::string lastEvent;           // the console's last line about the show
  bool paused = false;
  bool operator==(const ShowStatus&) const = default;
};

// A value one thread sets and another reads, each a whole copy under its lock.
template <class T>
class Shared {
 public:
  void set(T value) {
    std::lock_guard lock(mutex_);
    value_ = std::move(value);
  }
  [[nodiscard]] T get() const {
    std::lock_guard lock(mutex_);
    return value_;
  }

 private:
  mutable std::mutex mutex_;
  T value_{};
};

struct ControlState {
  Shared<Params> params;                     // as set, those waiting for the next film included
  Shared<ShowStatus> status;                 // after the last frame
  Shared<std::vector<std::string>> presets;  // the names of the saved presets
};

}  // namespace gb
