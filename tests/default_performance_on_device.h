#pragma once
// The README's default performance on the Vulkan backend with the stepper's work between steps on the device
// (everythingOnDevice), for the tests that check that work against the CPU's on the films the performance makes.

#include <memory>

#include "host/vulkan_stepper.h"
#include "scene/scene_file.h"
#include "simulation/simulation.h"
#include "tests/vulkan_test_device.h"

namespace gb::test {

// The frames the device tests look at: 40, the bag being drawn (an open film); 80, mid-stroke, the bag at its
// fastest; 110, the free bubble after the pinch-off (closed).
inline bool checkedFrame(int frame) { return frame == 40 || frame == 80 || frame == 110; }

// Plays the default performance to frame 110 on `device`, calling afterFrame(sim, the frame's wands, frame) after
// every frame. Returns the simulation as the last frame left it.
template <class AfterFrame>
std::unique_ptr<Simulation> playDefaultPerformanceOnDevice(const std::shared_ptr<const VulkanContext>& device,
                                                           AfterFrame afterFrame) {
  const Scene scene = resolveScene("default");
  const Params& p = scene.run.params;
  const GestureOptions& stroke = scene.run.gestureOptions;
  auto sim = std::make_unique<Simulation>(p, WandTool{}, gestureAt(Gesture::Giant, stroke, 0.0),
                                          std::make_unique<VulkanStepper>(device, everythingOnDevice()));
  for (int f = 1; f <= 110; ++f) {
    const WandState wands = gestureAt(Gesture::Giant, stroke, static_cast<double>(f) * p.frameTime);
    sim->advanceFrame(wands);
    afterFrame(*sim, wands, f);
  }
  return sim;
}

}  // namespace gb::test
