#include "host/device_buffer.h"

#include <cstring>
#include <span>
#include <stdexcept>

namespace gb {

namespace {

// Index buffer too: the film's triangles, wherever they are held, are the renderer's index buffer for the film.
constexpr auto kUsage = vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eIndexBuffer |
                        vk::BufferUsageFlagBits::eTransferSrc | vk::BufferUsageFlagBits::eTransferDst;

}  // namespace

DeviceBuffer::DeviceBuffer(const VulkanContext& context, vk::DeviceSize bytes, Placement placement)
    : context_(&context), size_(std::max<vk::DeviceSize>(bytes, 16)) {  // Vulkan forbids empty buffers
  buffer_ = vk::raii::Buffer(context.device, vk::BufferCreateInfo({}, size_, kUsage));
  const auto needs = buffer_.getMemoryRequirements();
  using Memory = vk::MemoryPropertyFlagBits;
  // Prefer memory that is both fast for the device and mappable (CPU drivers, integrated GPUs, resizable
  // BAR); fall back to device-only memory with staging copies.
  const vk::MemoryPropertyFlags deviceChoices[] = {Memory::eDeviceLocal | Memory::eHostVisible | Memory::eHostCoherent,
                                                   Memory::eDeviceLocal, Memory::eHostVisible | Memory::eHostCoherent};
  const vk::MemoryPropertyFlags hostChoices[] = {Memory::eHostVisible | Memory::eHostCoherent};
  const vk::MemoryPropertyFlags readbackChoices[] = {Memory::eHostVisible | Memory::eHostCoherent | Memory::eHostCached,
                                                     Memory::eHostVisible | Memory::eHostCoherent};
  const std::span<const vk::MemoryPropertyFlags> choices =
      placement == Placement::Device ? std::span<const vk::MemoryPropertyFlags>(deviceChoices)
      : placement == Placement::Host ? std::span<const vk::MemoryPropertyFlags>(hostChoices)
                                     : std::span<const vk::MemoryPropertyFlags>(readbackChoices);
  for (const auto wanted : choices) {
    const int type = context.memoryType(needs.memoryTypeBits, wanted);
    if (type < 0) continue;
    try {
      memory_ = vk::raii::DeviceMemory(context.device, vk::MemoryAllocateInfo(needs.size, static_cast<uint32_t>(type)));
    } catch (const vk::OutOfDeviceMemoryError&) {
      continue;  // e.g. a small BAR heap: try the next kind
    }
    buffer_.bindMemory(*memory_, 0);
    if (wanted & Memory::eHostVisible) mapped_ = memory_.mapMemory(0, size_);
    return;
  }
  throw std::runtime_error("Vulkan: no memory for a buffer of " + std::to_string(bytes) + " bytes");
}

void DeviceBuffer::copy(vk::Buffer from, vk::Buffer to, vk::DeviceSize bytes, vk::DeviceSize fromOffset,
                        vk::DeviceSize toOffset) const {
  vk::raii::CommandBuffer commands = context_->newCommandBuffer();
  commands.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  commands.copyBuffer(from, to, vk::BufferCopy(fromOffset, toOffset, bytes));
  commands.end();
  context_->submitAndWait(commands);
}

void DeviceBuffer::recordCopyFrom(const vk::raii::CommandBuffer& commands, const DeviceBuffer& from,
                                  vk::DeviceSize fromOffset, vk::DeviceSize bytes, vk::DeviceSize offset) const {
  if (bytes == 0) return;
  if (fromOffset + bytes > from.size_ || offset + bytes > size_)
    throw std::out_of_range("DeviceBuffer::recordCopyFrom past the end");
  commands.copyBuffer(from.handle(), handle(), vk::BufferCopy(fromOffset, offset, bytes));
}

void DeviceBuffer::write(const void* source, vk::DeviceSize bytes, vk::DeviceSize offset) {
  if (bytes == 0) return;
  if (offset + bytes > size_) throw std::out_of_range("DeviceBuffer::write past the end");
  if (mapped_) {
    std::memcpy(static_cast<char*>(mapped_) + offset, source, bytes);
    return;
  }
  DeviceBuffer staging(*context_, bytes, Placement::Host);
  std::memcpy(staging.mapped_, source, bytes);
  copy(staging.handle(), handle(), bytes, 0, offset);
}

void DeviceBuffer::read(void* destination, vk::DeviceSize bytes, vk::DeviceSize offset) const {
  if (bytes == 0) return;
  if (offset + bytes > size_) throw std::out_of_range("DeviceBuffer::read past the end");
  if (mapped_) {
    std::memcpy(destination, static_cast<const char*>(mapped_) + offset, bytes);
    return;
  }
  DeviceBuffer staging(*context_, bytes, Placement::Readback);
  copy(handle(), staging.handle(), bytes, offset, 0);
  std::memcpy(destination, staging.mapped_, bytes);
}

}  // namespace gb
