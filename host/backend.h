#pragma once
// Choosing the backend that steps the film.

#include <memory>
#include <string>

#include "host/vulkan_stepper.h"
#include "stages/stepper.h"

namespace gb {

enum class Backend { Cpu, Vulkan, Auto };

Backend backendFromName(const std::string& name);  // "cpu", "vulkan", "auto"; throws std::invalid_argument

// The stepper for a backend. Vulkan: the device chosen by `device` (see VulkanContext), throwing
// VulkanUnavailable with the reason when there is none. Auto: Vulkan when a GPU exists (or the device
// named by `device`), else the CPU: a software Vulkan driver is slower than the CPU backend.
// `report` says which was chosen and why, for the user. `betweenSteps` says where a Vulkan stepper finds the contacts
// and sums and checks the film between steps (VulkanStepperOptions).
std::unique_ptr<Stepper> makeStepper(Backend backend, const std::string& device, std::string& report,
                                     WorkPlace betweenSteps = WorkPlace::Automatic);

WorkPlace workPlaceFromName(const std::string& name);  // "auto", "device", "cpu"; throws std::invalid_argument

}  // namespace gb
