#pragma once
// How much of a run's wall time the simulation's step and the render were busy at once. The step is timed on the
// host around each frame's advance; the render is the device drawing each frame, from its own timestamps on the
// host's clock (Renderer::takeDrawnIntervals). On a CPU driver (lavapipe) both run on the same cores, so a large
// overlap is the render and the step sharing them rather than waiting for each other.

#include <chrono>
#include <string>
#include <vector>

#include "host/renderer.h"

namespace gb {

class StepRenderOverlap {
 public:
  using Interval = Renderer::BusyInterval;  // seconds of std::chrono::steady_clock
  void addStep(double start, double end);
  void addRender(const std::vector<Interval>& drawn);
  struct Totals {
    double step = 0, render = 0, both = 0;  // s: busy stepping, busy drawing, both at once
    bool renderTimed = false;               // the device's drawing was timed (false without calibrated timestamps)
  };
  [[nodiscard]] Totals totals() const;

 private:
  std::vector<Interval> steps_, renders_;
};

// "8.36 s of 16.23 s wall (51%); step 8.86 s, render 13.34 s", or why the render was not timed.
std::string describeOverlap(const StepRenderOverlap::Totals& totals, double wall);

// The steady clock's seconds since its epoch: the clock the renderer's device timestamps are read on.
double steadySeconds(std::chrono::steady_clock::time_point t);

}  // namespace gb
