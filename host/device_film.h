#pragma once
// The film as it lies in the Vulkan stepper's storage buffers, for the renderer to copy on the device (never
// through the host): positions, vertex normals and air flow as x, y, z blocks of `particles` floats, thickness one
// float per particle, triangles three indices each.

#include <cstdint>
#include <vulkan/vulkan.hpp>

namespace gb {

struct DeviceFilm {
  vk::Buffer position, normal, thickness, airFlow, triangles;
  uint32_t particleCount = 0;
  uint32_t triangleCount = 0;
};

}  // namespace gb
