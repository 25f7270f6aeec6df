#pragma once
// The Vulkan instance, the chosen device and its compute queue. Vulkan stays inside host/.

#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>
#include <vulkan/vulkan_raii.hpp>

#include "host/busy_interval.h"

namespace gb {

// No usable Vulkan: no loader, no driver, no device, or the requested device is not there.
class VulkanUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct VulkanDeviceInfo {
  uint32_t index = 0;
  std::string name;
  std::string type;  // "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other"
};

// Every Vulkan device the loader reports; empty (never throws) when there is no loader or driver.
std::vector<VulkanDeviceInfo> listVulkanDevices();

// Extensions beyond the compute set, e.g. for a window: the surface extensions GLFW asks for on the
// instance, VK_KHR_swapchain on the device.
struct VulkanExtensions {
  std::vector<const char*> instance;
  std::vector<const char*> device;
};

class VulkanContext {
 public:
  // Picks a device: `request` (or, when it is empty, the environment variable GIANTBUBBLE_VULKAN_DEVICE)
  // is a device index or a case-insensitive part of its name; without one, the first discrete GPU, then
  // integrated, virtual, CPU (lavapipe). GIANTBUBBLE_VULKAN_VALIDATION=1 enables the Khronos validation
  // layer when it is installed; its errors are printed and counted. The queue is the first family that does
  // graphics and compute (the renderer and the stepper share it), else the first that does compute.
  // Throws VulkanUnavailable, naming a missing extension.
  explicit VulkanContext(const std::string& request = "", const VulkanExtensions& extensions = {});

  // Submits a recorded command buffer and blocks until it has finished.
  void submitAndWait(const vk::raii::CommandBuffer& commands) const;
  // Submits without waiting: `done` (from newFence()) is signalled when the commands have finished, and
  // waitFor(done) blocks until then and resets it for the next submission. The caller keeps what the commands
  // read and write alive and unchanged until then.
  void submit(const vk::raii::CommandBuffer& commands, const vk::raii::Fence& done) const;
  void waitFor(const vk::raii::Fence& done) const;
  [[nodiscard]] vk::raii::Fence newFence() const;
  // A memory type index with all of `wanted`, or -1.
  [[nodiscard]] int memoryType(uint32_t typeBits, vk::MemoryPropertyFlags wanted) const;
  [[nodiscard]] vk::raii::CommandBuffer newCommandBuffer() const;

  [[nodiscard]] const VulkanDeviceInfo& info() const { return info_; }
  [[nodiscard]] bool validationEnabled() const { return validation_; }
  [[nodiscard]] size_t validationErrors() const { return *validationErrors_; }
  [[nodiscard]] double timestampPeriodNs() const { return timestampPeriodNs_; }
  // Device timestamps (vkCmdWriteTimestamp's ticks) on the host's steady clock (std::chrono::steady_clock's
  // seconds since its epoch), through one VK_EXT_calibrated_timestamps calibration; empty on a device without it.
  [[nodiscard]] std::vector<double> hostSecondsOfTimestamps(std::span<const uint64_t> ticks) const;
  // The interval between a query pool's two timestamps (a submission's first and last command, waited for) on the
  // host's clock; empty where they cannot be read there.
  [[nodiscard]] std::optional<DeviceBusyInterval> busyInterval(const vk::raii::QueryPool& firstAndLast) const;
  [[nodiscard]] bool timestampsOnHostClock() const { return hostClock_; }
  [[nodiscard]] uint32_t preferredWorkgroupSize() const;
  [[nodiscard]] uint32_t queueFamily() const { return queueFamily_; }

  vk::raii::Context context;
  vk::raii::Instance instance{nullptr};
  vk::raii::PhysicalDevice physical{nullptr};
  vk::raii::Device device{nullptr};
  vk::raii::Queue queue{nullptr};
  vk::raii::CommandPool commandPool{nullptr};

 private:
  VulkanDeviceInfo info_;
  uint32_t queueFamily_ = 0;
  bool validation_ = false;
  double timestampPeriodNs_ = 0.0;  // 0 when the queue has no timestamps
  bool hostClock_ = false;          // VK_EXT_calibrated_timestamps enabled, to CLOCK_MONOTONIC
  std::unique_ptr<size_t> validationErrors_ = std::make_unique<size_t>(0);  // stable address for the callback
  vk::raii::DebugUtilsMessengerEXT messenger_{nullptr};
  vk::raii::Fence fence_{nullptr};
};

}  // namespace gb
