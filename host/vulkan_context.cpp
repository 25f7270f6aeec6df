#include "host/vulkan_context.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>

namespace gb {

namespace {

std::string typeName(vk::PhysicalDeviceType type) {
  switch (type) {
    case vk::PhysicalDeviceType::eDiscreteGpu:
      return "discrete GPU";
    case vk::PhysicalDeviceType::eIntegratedGpu:
      return "integrated GPU";
    case vk::PhysicalDeviceType::eVirtualGpu:
      return "virtual GPU";
    case vk::PhysicalDeviceType::eCpu:
      return "CPU";
    default:
      return "other";
  }
}

// Lower rank is preferred: discrete, integrated, virtual, CPU, other.
int typeRank(vk::PhysicalDeviceType type) {
  switch (type) {
    case vk::PhysicalDeviceType::eDiscreteGpu:
      return 0;
    case vk::PhysicalDeviceType::eIntegratedGpu:
      return 1;
    case vk::PhysicalDeviceType::eVirtualGpu:
      return 2;
    case vk::PhysicalDeviceType::eCpu:
      return 3;
    default:
      return 4;
  }
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool envFlag(const char* name) {
  const char* v = std::getenv(name);
  return v && std::string(v) == "1";
}

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* errors) {
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    ++*static_cast<size_t*>(errors);
    std::fprintf(stderr, "vulkan validation error: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

bool layerAvailable(const vk::raii::Context& context, const char* name) {
  for (const auto& layer : context.enumerateInstanceLayerProperties())
    if (std::string(layer.layerName.data()) == name) return true;
  return false;
}

// The instance alone, for listing and choosing devices.
vk::raii::Instance makeInstance(const vk::raii::Context& context, bool validation,
                                std::vector<const char*> extensions = {}) {
  const vk::ApplicationInfo app("giantbubble", 1, "giantbubble", 1, VK_API_VERSION_1_1);
  std::vector<const char*> layers;
  if (validation) {
    layers.push_back("VK_LAYER_KHRONOS_validation");
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  return vk::raii::Instance(context, vk::InstanceCreateInfo({}, &app, layers, extensions));
}

}  // namespace

std::vector<VulkanDeviceInfo> listVulkanDevices() {
  std::vector<VulkanDeviceInfo> out;
  try {
    vk::raii::Context context;
    vk::raii::Instance instance = makeInstance(context, false);
    vk::raii::PhysicalDevices devices(instance);
    for (uint32_t i = 0; i < devices.size(); ++i) {
      const auto props = devices[i].getProperties();
      out.push_back({i, std::string(props.deviceName.data()), typeName(props.deviceType)});
    }
  } catch (const std::exception&) {
    out.clear();  // no loader, no driver: no devices
  }
  return out;
}

namespace {

// Whether the device's timestamps can be read against CLOCK_MONOTONIC (VK_EXT_calibrated_timestamps), the clock
// std::chrono::steady_clock reads on Linux.
bool canCalibrateToTheHostClock(const vk::raii::PhysicalDevice& physical) {
  const auto available = physical.enumerateDeviceExtensionProperties();
  if (std::none_of(available.begin(), available.end(), [](const auto& e) {
        return std::string(e.extensionName.data()) == VK_EXT_CALIBRATED_TIMESTAMPS_EXTENSION_NAME;
      }))
    return false;
  const auto domains = physical.getCalibrateableTimeDomainsEXT();
  const auto has = [&](vk::TimeDomainEXT d) { return std::find(domains.begin(), domains.end(), d) != domains.end(); };
  return has(vk::TimeDomainEXT::eDevice) && has(vk::TimeDomainEXT::eClockMonotonic);
}

}  // namespace

VulkanContext::VulkanContext(const std::string& requestArg, const VulkanExtensions& extensions) try {
  std::string request = requestArg;
  if (request.empty())
    if (const char* env = std::getenv("GIANTBUBBLE_VULKAN_DEVICE")) request = env;
  validation_ = envFlag("GIANTBUBBLE_VULKAN_VALIDATION") && layerAvailable(context, "VK_LAYER_KHRONOS_validation");
  instance = makeInstance(context, validation_, extensions.instance);
  if (validation_) {
    using Severity = vk::DebugUtilsMessageSeverityFlagBitsEXT;
    using Type = vk::DebugUtilsMessageTypeFlagBitsEXT;
    messenger_ = vk::raii::DebugUtilsMessengerEXT(
        instance, vk::DebugUtilsMessengerCreateInfoEXT({}, Severity::eWarning | Severity::eError,
                                                       Type::eGeneral | Type::eValidation | Type::ePerformance,
                                                       &onValidationMessage, validationErrors_.get()));
  }

  vk::raii::PhysicalDevices devices(instance);
  if (devices.empty()) throw VulkanUnavailable("no Vulkan device (install mesa-vulkan-drivers for lavapipe)");
  int chosen = -1;
  if (!request.empty()) {
    const bool isIndex = std::all_of(request.begin(), request.end(), [](unsigned char c) { return std::isdigit(c); });
    for (uint32_t i = 0; i < devices.size() && chosen < 0; ++i) {
      const std::string name = devices[i].getProperties().deviceName.data();
      if (isIndex ? std::stoul(request) == i : lower(name).find(lower(request)) != std::string::npos)
        chosen = static_cast<int>(i);
    }
    if (chosen < 0) throw VulkanUnavailable("no Vulkan device matches '" + request + "'");
  } else {
    for (uint32_t i = 0; i < devices.size(); ++i)
      if (chosen < 0 || typeRank(devices[i].getProperties().deviceType) <
                            typeRank(devices[static_cast<uint32_t>(chosen)].getProperties().deviceType))
        chosen = static_cast<int>(i);
  }
  physical = std::move(devices[static_cast<uint32_t>(chosen)]);
  const auto props = physical.getProperties();
  info_ = {static_cast<uint32_t>(chosen), std::string(props.deviceName.data()), typeName(props.deviceType)};

  const auto families = physical.getQueueFamilyProperties();
  using Q = vk::QueueFlagBits;
  auto compute = std::find_if(families.begin(), families.end(), [](const auto& f) {
    return (f.queueFlags & (Q::eCompute | Q::eGraphics)) == (Q::eCompute | Q::eGraphics);
  });
  if (compute == families.end())
    compute =
        std::find_if(families.begin(), families.end(), [](const auto& f) { return bool(f.queueFlags & Q::eCompute); });
  if (compute == families.end()) throw VulkanUnavailable("device " + info_.name + " has no compute queue");
  queueFamily_ = static_cast<uint32_t>(compute - families.begin());
  if (compute->timestampValidBits > 0) timestampPeriodNs_ = props.limits.timestampPeriod;

  const float priority = 1.0f;
  const vk::DeviceQueueCreateInfo queueInfo({}, queueFamily_, 1, &priority);
  for (const char* wanted : extensions.device) {
    const auto available = physical.enumerateDeviceExtensionProperties();
    if (std::none_of(available.begin(), available.end(),
                     [&](const auto& e) { return std::string(e.extensionName.data()) == wanted; }))
      throw VulkanUnavailable("device " + info_.name + " lacks the extension " + wanted);
  }
  std::vector<const char*> deviceExtensions = extensions.device;
  hostClock_ = timestampPeriodNs_ > 0 && canCalibrateToTheHostClock(physical);
  if (hostClock_) deviceExtensions.push_back(VK_EXT_CALIBRATED_TIMESTAMPS_EXTENSION_NAME);
  device = vk::raii::Device(physical, vk::DeviceCreateInfo({}, queueInfo, {}, deviceExtensions));
  queue = vk::raii::Queue(device, queueFamily_, 0);
  commandPool = vk::raii::CommandPool(device, {vk::CommandPoolCreateFlagBits::eResetCommandBuffer, queueFamily_});
  fence_ = vk::raii::Fence(device, vk::FenceCreateInfo());
} catch (const VulkanUnavailable&) {
  throw;
} catch (const std::exception& e) {
  throw VulkanUnavailable(std::string("Vulkan could not start: ") + e.what());
}

vk::raii::CommandBuffer VulkanContext::newCommandBuffer() const {
  vk::raii::CommandBuffers buffers(device, {*commandPool, vk::CommandBufferLevel::ePrimary, 1});
  return std::move(buffers.front());
}

void VulkanContext::submitAndWait(const vk::raii::CommandBuffer& commands) const {
  submit(commands, fence_);
  waitFor(fence_);
}

void VulkanContext::submit(const vk::raii::CommandBuffer& commands, const vk::raii::Fence& done) const {
  const vk::CommandBuffer handle = *commands;
  queue.submit(vk::SubmitInfo({}, {}, handle), *done);
}

void VulkanContext::waitFor(const vk::raii::Fence& done) const {
  if (device.waitForFences({*done}, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
    throw std::runtime_error("Vulkan: waiting for the GPU failed");
  device.resetFences({*done});
}

std::optional<DeviceBusyInterval> VulkanContext::busyInterval(const vk::raii::QueryPool& firstAndLast) const {
  const auto [result, ticks] =
      firstAndLast.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t), vk::QueryResultFlagBits::e64);
  if (result != vk::Result::eSuccess) return std::nullopt;
  const std::vector<double> seconds = hostSecondsOfTimestamps(ticks);
  if (seconds.size() != 2 || seconds[1] < seconds[0]) return std::nullopt;
  return DeviceBusyInterval{seconds[0], seconds[1]};
}

std::vector<double> VulkanContext::hostSecondsOfTimestamps(std::span<const uint64_t> ticks) const {
  if (!hostClock_) return {};
  const std::array<vk::CalibratedTimestampInfoEXT, 2> domains{
      vk::CalibratedTimestampInfoEXT(vk::TimeDomainEXT::eDevice),
      vk::CalibratedTimestampInfoEXT(vk::TimeDomainEXT::eClockMonotonic)};
  const auto [now, deviation] = device.getCalibratedTimestampsEXT(domains);
  (void)deviation;  // nanoseconds on lavapipe, microseconds on a GPU: far below a frame
  std::vector<double> seconds;
  for (const uint64_t t : ticks) {
    const double deviceNs = static_cast<double>(static_cast<int64_t>(t - now[0])) * timestampPeriodNs_;
    seconds.push_back((static_cast<double>(now[1]) + deviceNs) * 1e-9);
  }
  return seconds;
}

vk::raii::Fence VulkanContext::newFence() const { return vk::raii::Fence(device, vk::FenceCreateInfo()); }

int VulkanContext::memoryType(uint32_t typeBits, vk::MemoryPropertyFlags wanted) const {
  const auto memory = physical.getMemoryProperties();
  for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & wanted) == wanted) return static_cast<int>(i);
  return -1;
}

uint32_t VulkanContext::preferredWorkgroupSize() const {
  if (const char* env = std::getenv("GIANTBUBBLE_VULKAN_WORKGROUP")) {
    const long size = std::strtol(env, nullptr, 10);
    if (size >= 1 && size <= 1024) return static_cast<uint32_t>(size);
  }
  // A CPU driver runs a workgroup as SIMD batches on one thread: 64 keeps every core busy at 10k particles.
  // A GPU wants enough warps per workgroup to hide memory latency.
  return info_.type == "CPU" ? 64u : 256u;
}

}  // namespace gb
