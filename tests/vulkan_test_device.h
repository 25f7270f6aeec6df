#pragma once
// The Vulkan device the equivalence tests run on (lavapipe in CI). Under CI=true a missing device fails the
// test; elsewhere the test is skipped with a loud message.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "host/vulkan_context.h"
#include "host/vulkan_stepper.h"

namespace gb::test {

inline bool underCi() {
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}

// The one device every test of the process shares, created on first use.
inline std::shared_ptr<const VulkanContext>& sharedVulkanDevice() {
  static std::shared_ptr<const VulkanContext> device;
  return device;
}

// Releases the shared device when the tests are over, before static destructors run: a real GPU's driver
// tears its own state down at exit (the NVIDIA driver crashed the test process there when the device was
// destroyed after it), while lavapipe did not mind either order.
class ReleaseVulkanDeviceAfterTests : public ::testing::Environment {
 public:
  void TearDown() override { sharedVulkanDevice().reset(); }
};

// Shared by every test of the process; created once with the validation layer on when it is installed.
inline std::shared_ptr<const VulkanContext> vulkanDevice(std::string& whyNot) {
  std::shared_ptr<const VulkanContext>& device = sharedVulkanDevice();
  static std::string reason;
  static bool tried = false;
  if (!tried) {
    tried = true;
    ::testing::AddGlobalTestEnvironment(new ReleaseVulkanDeviceAfterTests);
    setenv("GIANTBUBBLE_VULKAN_VALIDATION", "1", 0);
    try {
      device = std::make_shared<const VulkanContext>();
      std::fprintf(stderr, "Vulkan tests on %s (%s), validation layer %s\n", device->info().name.c_str(),
                   device->info().type.c_str(), device->validationEnabled() ? "on" : "not installed");
    } catch (const VulkanUnavailable& e) {
      reason = e.what();
    }
  }
  whyNot = reason;
  return device;
}

// The stepper's work between steps on the device whatever the device: on a CPU driver (lavapipe) Automatic would
// leave the contact search and the statistics to the CPU, and the tests of the device's own would test nothing.
inline VulkanStepperOptions everythingOnDevice() {
  VulkanStepperOptions options;
  options.contactSearch = WorkPlace::Device;
  options.statistics = WorkPlace::Device;
  return options;
}

// The stepper's work between steps on the CPU whatever the device: on a GPU Automatic would put it on the device,
// and the state would stay there on frames where no rule acts.
inline VulkanStepperOptions everythingOnCpu() {
  VulkanStepperOptions options;
  options.contactSearch = WorkPlace::Cpu;
  options.statistics = WorkPlace::Cpu;
  return options;
}

}  // namespace gb::test

// Gets the device into `var`, or fails (CI) / skips loudly (elsewhere).
#define GB_REQUIRE_VULKAN(var)                                                                            \
  std::string gbWhyNot_;                                                                                  \
  const auto var = ::gb::test::vulkanDevice(gbWhyNot_);                                                   \
  if (!var) {                                                                                             \
    if (::gb::test::underCi()) FAIL() << "CI=true but no Vulkan device: " << gbWhyNot_;                   \
    std::fprintf(stderr, "\n*** SKIPPING Vulkan test: no Vulkan device (%s) ***\n\n", gbWhyNot_.c_str()); \
    GTEST_SKIP() << "no Vulkan device: " << gbWhyNot_;                                                    \
  }
