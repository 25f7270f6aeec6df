#pragma once
// A storage buffer on the device that owns its memory (one owner, move-only like the vk::raii handles in
// it). Host-visible memory is mapped once and copied directly; device-only memory goes through a staging
// buffer.

#include <vulkan/vulkan_raii.hpp>

#include "host/vulkan_context.h"

namespace gb {

class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  // Where the memory lives: fast for the device (mapped too when the device allows), host memory the device
  // reads over the bus (staging for uploads), or host memory the CPU reads back fast (cached where the driver
  // has such memory: reading write-combined or the device's own memory through a mapping runs at uncached speed).
  enum class Placement { Device, Host, Readback };
  DeviceBuffer(const VulkanContext& context, vk::DeviceSize bytes, Placement placement = Placement::Device);

  void write(const void* source, vk::DeviceSize bytes, vk::DeviceSize offset = 0);
  void read(void* destination, vk::DeviceSize bytes, vk::DeviceSize offset = 0) const;

  // Records a copy of `bytes` from `fromOffset` in `from` to `offset` in this buffer, for a batch of copies in one
  // submission (the caller submits and waits before reading).
  void recordCopyFrom(const vk::raii::CommandBuffer& commands, const DeviceBuffer& from, vk::DeviceSize fromOffset,
                      vk::DeviceSize bytes, vk::DeviceSize offset) const;

  [[nodiscard]] vk::Buffer handle() const { return *buffer_; }
  [[nodiscard]] vk::DeviceSize size() const { return size_; }

 private:
  void copy(vk::Buffer from, vk::Buffer to, vk::DeviceSize bytes, vk::DeviceSize fromOffset,
            vk::DeviceSize toOffset) const;

  const VulkanContext* context_ = nullptr;
  vk::DeviceSize size_ = 0;
  vk::raii::Buffer buffer_{nullptr};
  vk::raii::DeviceMemory memory_{nullptr};
  void* mapped_ = nullptr;
};

}  // namespace gb
