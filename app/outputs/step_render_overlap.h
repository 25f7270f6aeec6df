#pragma once
// How much of a run's wall time the simulation's step and the render were busy at once. The render is the device
// drawing each frame, from its own timestamps on the host's clock (Renderer::takeDrawnIntervals). The step is the
// Vulkan stepper's batch on the device, timed the same way (VulkanStepper::lastStepOnDevice): on one queue a batch
// submitted behind a frame being drawn waits for it, and waiting is not working at once. Elsewhere (the CPU
// backend, a device without such timestamps) it is timed on the host around each frame's advance. On a CPU driver
// (lavapipe) the CPU backend's step and the render run on the same cores, so a large overlap is the two sharing them
// rather than waiting for each other.

#include <chrono>
#include <string>
#include <vector>

#include "host/renderer.h"
#include "stages/stepper.h"

namespace gb {

class StepRenderOverlap {
 public:
  using Interval = Renderer::BusyInterval;  // seconds of std::chrono::steady_clock
  void addStep(double start, double end);
  // A frame's step by `stepper`, advanced on the host from `start` to `end` (seconds of the steady clock): the
  // device's interval where it has one, else the host's.
  void addStep(const Stepper& stepper, double start, double end);
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
