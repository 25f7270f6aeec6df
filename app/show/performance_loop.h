#pragma once
// A stage that is never empty (giantbubble live): with a scripted or recorded input (script:, trajectory:,
// fakenect:) the performance loops. Once it has played and the wands hold no film (the bubble flies free, or it is
// gone) the wands return to where the performance starts; once the stage has been empty for --auto-dip seconds they
// dip there and the performance plays again from its start. A camera or the mouse is a performer, who returns and
// dips by themselves: with them the wands dip again where they are (live_show.cpp).
//
// The return is a smoothstep between the two poses, so the wands never jump: its length is the farther tip's way at
// kReturnSpeed, at least kShortestReturn.

#include "model/wire_frame.h"

namespace gb {

class PerformanceLoop {
 public:
  static constexpr double kReturnSpeed = 1.5;     // m/s of the farther tip, a performer walking back
  static constexpr double kShortestReturn = 0.5;  // s: a short way is still a visible move, not a jump

  // What the show does this frame.
  enum class Action {
    Play,          // the wands follow the input
    StartReturn,   // open the input again from its start and call startReturn with its first pose
    Return,        // the wands follow returnWands(t)
    StartPlaying,  // the input's time 0 is now (a film hangs on the wands: one dipped by hand during the return)
    DipAndPlay,    // dip a new film at the start pose, and the input's time 0 is now
  };

  // autoDip: seconds of empty stage before the wands dip again (negative: never, and the performance never loops).
  explicit PerformanceLoop(double autoDip) : autoDip_(autoDip) {}

  // The next action at show time t (s). performanceOver: the input has played to its end (a script past its
  // stroke, a file or recording ended); wandsFree: no film hangs on the wands (a free bubble, or none);
  // emptySince: show time the stage became empty, negative while a film is on it.
  Action next(double t, bool performanceOver, bool wandsFree, double emptySince);
  // The return from `from` (where the wands are) to `to` (the input's first pose) starts at t.
  void startReturn(double t, const WandState& from, const WandState& to);
  // The wands during the return at time t (the start pose once it is over; velocities the path's derivative).
  [[nodiscard]] WandState returnWands(double t) const;
  // The performance plays again from its start (a dip and play, or R: the input restarted by hand).
  void restart() { phase_ = Phase::Playing; }
  [[nodiscard]] bool looping() const { return phase_ != Phase::Playing; }
  [[nodiscard]] double returnSeconds() const { return end_ - begin_; }

 private:
  enum class Phase { Playing, Returning, AtStart };
  double autoDip_;
  Phase phase_ = Phase::Playing;
  double begin_ = 0, end_ = 0;
  WandState from_, to_;
};

}  // namespace gb
