#include "host/backend.h"

#include <stdexcept>

#include "host/vulkan_context.h"
#include "host/vulkan_stepper.h"
#include "stages/cpu_stepper.h"

namespace gb {

Backend backendFromName(const std::string& name) {
  if (name == "cpu") return Backend::Cpu;
  if (name == "vulkan") return Backend::Vulkan;
  if (name == "auto") return Backend::Auto;
  throw std::invalid_argument("unknown backend '" + name + "' (choices: cpu, vulkan, auto)");
}

WorkPlace workPlaceFromName(const std::string& name) {
  if (name == "auto") return WorkPlace::Automatic;
  if (name == "device") return WorkPlace::Device;
  if (name == "cpu") return WorkPlace::Cpu;
  throw std::invalid_argument("unknown place '" + name + "' (choices: auto, device, cpu)");
}

std::unique_ptr<Stepper> makeStepper(Backend backend, const std::string& device, std::string& report,
                                     WorkPlace betweenSteps) {
  if (backend == Backend::Cpu) {
    report = "backend: cpu (requested)";
    return std::make_unique<CpuStepper>();
  }
  try {
    auto context = std::make_shared<const VulkanContext>(device);
    // A software Vulkan driver (lavapipe) runs the shaders on the same cores as the CPU backend, 2.6 to 5
    // times slower (docs/performance.md); auto takes it only when asked for by name.
    if (backend == Backend::Auto && context->info().type == "CPU" && device.empty()) {
      report = "backend: cpu (auto: the only Vulkan device, " + context->info().name +
               ", is a CPU driver, slower than the CPU backend; use --backend vulkan to run on it)";
      return std::make_unique<CpuStepper>();
    }
    VulkanStepperOptions options;
    options.contactSearch = options.statistics = betweenSteps;
    auto stepper = std::make_unique<VulkanStepper>(std::move(context), options);
    const char* why = backend == Backend::Vulkan ? ""
                      : device.empty()           ? " (auto: a Vulkan GPU exists)"
                                                 : " (auto: the requested device)";
    report = "backend: " + stepper->name() + why;
    return stepper;
  } catch (const VulkanUnavailable& e) {
    if (backend == Backend::Vulkan) throw;
    report = std::string("backend: cpu (auto: ") + e.what() + ")";
    return std::make_unique<CpuStepper>();
  }
}

}  // namespace gb
