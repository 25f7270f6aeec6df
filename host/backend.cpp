#include "backend.h"

#include <stdexcept>

#include "cpu_stepper.h"
#include "vulkan_context.h"
#include "vulkan_stepper.h"

namespace gb {

Backend backendFromName(const std::string& name) {
  if (name == "cpu") return Backend::Cpu;
  if (name == "vulkan") return Backend::Vulkan;
  if (name == "auto") return Backend::Auto;
  throw std::invalid_argument("unknown backend '" + name + "' (choices: cpu, vulkan, auto)");
}

std::unique_ptr<Stepper> makeStepper(Backend backend, const std::string& device, std::string& report) {
  if (backend == Backend::Cpu) {
    report = "backend: cpu (requested)";
    return std::make_unique<CpuStepper>();
  }
  try {
    auto stepper = std::make_unique<VulkanStepper>(std::make_shared<const VulkanContext>(device));
    report = "backend: " + stepper->name() + (backend == Backend::Auto ? " (auto: a Vulkan device exists)" : "");
    return stepper;
  } catch (const VulkanUnavailable& e) {
    if (backend == Backend::Vulkan) throw;
    report = std::string("backend: cpu (auto: ") + e.what() + ")";
    return std::make_unique<CpuStepper>();
  }
}

}  // namespace gb
