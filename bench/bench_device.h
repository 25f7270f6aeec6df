#pragma once
// The Vulkan device the benchmarks run on, made once; null (with a loud message) when there is none.

#include <cstdio>
#include <memory>

#include "host/vulkan_context.h"

namespace gb::bench {

inline std::shared_ptr<const VulkanContext> vulkanDevice() {
  static std::shared_ptr<const VulkanContext> device = [] {
    try {
      return std::make_shared<const VulkanContext>();
    } catch (const VulkanUnavailable& e) {
      std::fprintf(stderr, "*** Vulkan benchmarks skipped: %s ***\n", e.what());
      return std::shared_ptr<const VulkanContext>();
    }
  }();
  return device;
}

}  // namespace gb::bench
