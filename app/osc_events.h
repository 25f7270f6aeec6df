#pragma once
// Show control (beyond the paper): the run's events and the bubble's size and position as OSC messages over
// UDP (liblo), so that sound and light can follow the bubble. Off unless a target is given (--osc HOST:PORT).
//
//   /giantbubble/event  ,sd   name, time (s)     film_created, poked, film_grown, pinched_off,
//                                                burst_started, burst_finished; live only:
//                                                simulation_unstable, input_lost, input_back
//   /giantbubble/bubble ,dffffff  time (s), centre x y z (m, world), area (m^2), volume (m^3), solution left
//
// docs/formats.md describes them.

#include <memory>
#include <string>

#include "simulation.h"
#include "state.h"

namespace gb {

class OscSender {
 public:
  // target is HOST:PORT; throws std::invalid_argument naming it when it cannot be used.
  explicit OscSender(const std::string& target);
  ~OscSender();
  OscSender(const OscSender&) = delete;
  OscSender& operator=(const OscSender&) = delete;

  // Each returns false (and keeps going) when the message could not be sent: a show must not stop because
  // the light desk is unplugged. lastError() says why.
  bool event(const std::string& name, double time);
  bool bubble(double time, const Vec3& centre, double area, double volume, double solution);
  [[nodiscard]] const std::string& lastError() const { return lastError_; }

 private:
  struct Address;
  std::unique_ptr<Address> address_;
  std::string lastError_;
};

// What a run or the live window sends each frame when OSC is on (target non-empty): the frame's events and the
// bubble's state. A failed send is reported once on stderr and the show goes on.
class ShowControl {
 public:
  explicit ShowControl(const std::string& target);
  void frame(const Simulation& sim, const FrameStats& stats, const std::string& events);

 private:
  std::unique_ptr<OscSender> sender_;
  bool warned_ = false;
};

}  // namespace gb
