#pragma once
// Choosing the backend that steps the film.

#include <memory>
#include <string>

#include "stepper.h"

namespace gb {

enum class Backend { Cpu, Vulkan, Auto };

Backend backendFromName(const std::string& name);  // "cpu", "vulkan", "auto"; throws std::invalid_argument

// The stepper for a backend. Vulkan: the device chosen by `device` (see VulkanContext), throwing
// VulkanUnavailable with the reason when there is none. Auto: Vulkan when a GPU exists (or the device
// named by `device`), else the CPU: a software Vulkan driver is slower than the CPU backend.
// `report` says which was chosen and why, for the user.
std::unique_ptr<Stepper> makeStepper(Backend backend, const std::string& device, std::string& report);

}  // namespace gb
