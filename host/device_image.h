#pragma once
// A 2-D image on the device that owns its memory and view (move-only like the vk::raii handles in it), and the
// upload of a texture's texels.

#include <cstdint>
#include <vector>
#include <vulkan/vulkan_raii.hpp>

#include "host/vulkan_context.h"

namespace gb {

class DeviceImage {
 public:
  DeviceImage() = default;
  // `samples` > 1: a multisampled render target (resolved into a single-sampled image to be read).
  DeviceImage(const VulkanContext& context, vk::Extent2D extent, vk::Format format, vk::ImageUsageFlags usage,
              vk::ImageAspectFlags aspect = vk::ImageAspectFlagBits::eColor,
              vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1);

  [[nodiscard]] vk::Image handle() const { return *image_; }
  [[nodiscard]] vk::ImageView view() const { return *view_; }
  [[nodiscard]] vk::Extent2D extent() const { return extent_; }

 private:
  vk::Extent2D extent_;
  vk::raii::Image image_{nullptr};
  vk::raii::DeviceMemory memory_{nullptr};
  vk::raii::ImageView view_{nullptr};
};

// IEEE half precision of a float (round to nearest; tiny values flush to zero, huge ones saturate).
uint16_t toHalf(float value);

// A sampled RGBA16F texture holding `rgba` (4 floats per texel, row-major), ready in shader-read layout.
DeviceImage uploadTexture(const VulkanContext& context, int width, int height, const std::vector<float>& rgba);

// Records a layout change of a whole colour image with the given access scopes.
void transitionImage(const vk::raii::CommandBuffer& commands, vk::Image image, vk::ImageLayout from, vk::ImageLayout to,
                     vk::PipelineStageFlags srcStage, vk::AccessFlags srcAccess, vk::PipelineStageFlags dstStage,
                     vk::AccessFlags dstAccess);

}  // namespace gb
