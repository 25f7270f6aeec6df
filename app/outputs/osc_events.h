#pragma once
// Show control (beyond the paper): the run's events and the bubble's size and position as OSC messages over
// UDP (liblo), so that sound and light can follow the bubble. Off unless a target is given (--osc HOST:PORT).
//
//   /giantbubble/event  ,sd   name, time (s)     film_created, poked, film_grown, pinched_off,
//                                                burst_started, burst_by_CAUSE (wand, touch, floor,
//                                                thin, impact, poke, cue), burst_finished; live only:
//                                                simulation_unstable, input_lost, input_back
//   /giantbubble/bubble ,dffffff  time (s), centre x y z (m, world), area (m^2), volume (m^3), solution left
//   /giantbubble/touch  ,dffff  time (s), x y z (m, world), approach (m/s)   the performer's touch that burst it
//   /giantbubble/cue    ,ssd  cue, what was done, time (s)   live --osc-in: each cue taken (osc_cues.h)
//   /giantbubble/performer ,ss  state, detail   live with a camera: waiting (why, or the set-up's count), found,
//                                                left_hand_lost, right_hand_lost, hands_back
//   /joint              ,sifff  l_hand or r_hand, user 1, x y z   live: the performer's hands as a Kinect skeleton
//                                                tracker (OSCeleton) sends them: x 0..1 across the camera's image
//                                                left to right (+-1.28 m), y 0..1 top to bottom (+-0.96 m), z the
//                                                depth in metres x 0.78125 (0..7 for 0..9 m)
//
// docs/formats.md describes them.

#include <lo/lo.h>

#include <array>
#include <memory>
#include <string>

#include "capture/hand_source.h"
#include "model/state.h"
#include "simulation/simulation.h"

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
  bool touch(double time, const Vec3& position, float approachSpeed);
  bool cue(const std::string& name, const std::string& done, double time);
  bool joint(const std::string& name, int user, const std::array<float, 3>& position);
  bool performer(const std::string& state, const std::string& detail);
  [[nodiscard]] const std::string& lastError() const { return lastError_; }

 private:
  struct Address;
  bool send(const char* path, lo_message message);  // sends and frees the message
  std::unique_ptr<Address> address_;
  std::string lastError_;
};

// What a run or the live window sends each frame when OSC is on (target non-empty): the frame's events and the
// bubble's state. A failed send is reported once on stderr and the show goes on.
class ShowControl {
 public:
  explicit ShowControl(const std::string& target);
  void frame(const Simulation& sim, const FrameStats& stats, const std::string& events);
  // A cue taken from --osc-in and what it did ("new film", "no film to burst").
  void cue(const std::string& name, const std::string& done, double time);
  // The performer's hands in camera space (kinect_depth.h; m), as OSCeleton joints; a hand not finite is not sent.
  void hands(const Vec3d& left, const Vec3d& right);
  // Where the performer stands with the show: waiting (and why), found, a hand lost or back (the list above).
  void performer(const std::string& state, const std::string& detail);

 private:
  std::unique_ptr<OscSender> sender_;
  bool warned_ = false;
  void check(bool sent);
};

// A camera-space point (m) in OSCeleton's normalized coordinates (the /joint message above).
std::array<float, 3> oscCeletonPosition(const Vec3d& camera);

}  // namespace gb
