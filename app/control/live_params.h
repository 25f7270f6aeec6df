#pragma once
// Parameters set while the show runs (OSC /giantbubble/param/NAME, presets): each set is checked as --param checks
// it (setParameter) and reported; the accepted ones reach the simulation between frames (apply), those that shape
// a film as it is made at the next dip (beforeDip), so the CPU and Vulkan backends see a parameter change at the
// same point of the show.

#include <string>
#include <vector>

#include "model/params.h"

namespace gb {

class Simulation;

class LiveParams {
 public:
  // `wanted` is the show's parameter block (the one a new simulation is made with): sets change it.
  explicit LiveParams(Params& wanted) : wanted_(wanted) {}

  // Sets NAME to value. Returns the report: "param NAME = VALUE" with when it takes effect, or "param NAME refused:
  // why" (unknown, out of range, not a whole number, fixed at start); `refused` says which.
  std::string set(const std::string& name, double value, bool& refused);

  // The parameters set since the last call, into the simulation (their reports when that fails: the explicit
  // integrator cannot keep the film stable with them). Call between frames.
  std::vector<std::string> apply(Simulation& sim);
  // Before a dip: the parameters waiting for the next film, into the simulation.
  std::vector<std::string> beforeDip(Simulation& sim);

  [[nodiscard]] const Params& wanted() const { return wanted_; }
  [[nodiscard]] long accepted() const { return accepted_; }
  [[nodiscard]] long refused() const { return refused_; }

 private:
  Params& wanted_;
  bool liveChanged_ = false, nextFilmChanged_ = false;
  long accepted_ = 0, refused_ = 0;
  std::vector<std::string> load(Simulation& sim, const Params& params);
};

}  // namespace gb
