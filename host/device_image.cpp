#include "host/device_image.h"

#include <bit>
#include <cmath>
#include <stdexcept>

#include "host/device_buffer.h"

namespace gb {

DeviceImage::DeviceImage(const VulkanContext& context, vk::Extent2D extent, vk::Format format,
                         vk::ImageUsageFlags usage, vk::ImageAspectFlags aspect, vk::SampleCountFlagBits samples)
    : extent_(extent) {
  image_ = vk::raii::Image(
      context.device, vk::ImageCreateInfo({}, vk::ImageType::e2D, format, vk::Extent3D(extent.width, extent.height, 1),
                                          1, 1, samples, vk::ImageTiling::eOptimal, usage, vk::SharingMode::eExclusive,
                                          {}, vk::ImageLayout::eUndefined));
  const auto needs = image_.getMemoryRequirements();
  const int type = context.memoryType(needs.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal);
  if (type < 0) throw std::runtime_error("Vulkan: no device memory for an image");
  memory_ = vk::raii::DeviceMemory(context.device, vk::MemoryAllocateInfo(needs.size, static_cast<uint32_t>(type)));
  image_.bindMemory(*memory_, 0);
  view_ = vk::raii::ImageView(context.device, vk::ImageViewCreateInfo({}, *image_, vk::ImageViewType::e2D, format, {},
                                                                      vk::ImageSubresourceRange(aspect, 0, 1, 0, 1)));
}

uint16_t toHalf(float value) {
  const uint32_t bits = std::bit_cast<uint32_t>(value);
  const uint32_t sign = (bits >> 16) & 0x8000u;
  const float magnitude = std::fabs(value);
  if (!(magnitude < 65504.0f)) return static_cast<uint16_t>(sign | 0x7bffu);  // saturate (NaN too: never stored)
  if (magnitude < 6.103515625e-05f) return static_cast<uint16_t>(sign);       // below the smallest normal half
  const int exponent = static_cast<int>((bits >> 23) & 0xffu) - 127 + 15;
  uint32_t mantissa = bits & 0x7fffffu;
  uint32_t half = (static_cast<uint32_t>(exponent) << 10) | (mantissa >> 13);
  if ((mantissa & 0x1fffu) > 0x1000u || ((mantissa & 0x1fffu) == 0x1000u && (half & 1u))) ++half;  // to nearest even
  return static_cast<uint16_t>(sign | half);
}

void transitionImage(const vk::raii::CommandBuffer& commands, vk::Image image, vk::ImageLayout from, vk::ImageLayout to,
                     vk::PipelineStageFlags srcStage, vk::AccessFlags srcAccess, vk::PipelineStageFlags dstStage,
                     vk::AccessFlags dstAccess) {
  const vk::ImageMemoryBarrier barrier(srcAccess, dstAccess, from, to, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED,
                                       image, vk::ImageSubresourceRange(vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1));
  commands.pipelineBarrier(srcStage, dstStage, {}, {}, {}, barrier);
}

DeviceImage uploadTexture(const VulkanContext& context, int width, int height, const std::vector<float>& rgba) {
  const vk::Extent2D extent(static_cast<uint32_t>(width), static_cast<uint32_t>(height));
  DeviceImage image(context, extent, vk::Format::eR16G16B16A16Sfloat,
                    vk::ImageUsageFlagBits::eSampled | vk::ImageUsageFlagBits::eTransferDst);
  std::vector<uint16_t> halves(rgba.size());
  for (size_t i = 0; i < rgba.size(); ++i) halves[i] = toHalf(rgba[i]);
  DeviceBuffer staging(context, halves.size() * sizeof(uint16_t), DeviceBuffer::Placement::Host);
  staging.write(halves.data(), halves.size() * sizeof(uint16_t));
  vk::raii::CommandBuffer commands = context.newCommandBuffer();
  commands.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  using Stage = vk::PipelineStageFlagBits;
  using Access = vk::AccessFlagBits;
  transitionImage(commands, image.handle(), vk::ImageLayout::eUndefined, vk::ImageLayout::eTransferDstOptimal,
                  Stage::eTopOfPipe, {}, Stage::eTransfer, Access::eTransferWrite);
  commands.copyBufferToImage(staging.handle(), image.handle(), vk::ImageLayout::eTransferDstOptimal,
                             vk::BufferImageCopy(0, 0, 0, {vk::ImageAspectFlagBits::eColor, 0, 0, 1}, {0, 0, 0},
                                                 vk::Extent3D(extent.width, extent.height, 1)));
  transitionImage(commands, image.handle(), vk::ImageLayout::eTransferDstOptimal,
                  vk::ImageLayout::eShaderReadOnlyOptimal, Stage::eTransfer, Access::eTransferWrite,
                  Stage::eFragmentShader, Access::eShaderRead);
  commands.end();
  context.submitAndWait(commands);
  return image;
}

}  // namespace gb
