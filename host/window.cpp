#include "host/window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "host/banner_text.h"
#include "host/device_buffer.h"
#include "host/device_image.h"

namespace gb {

namespace {

// GLFW's library state: one init per window's lifetime is enough for this program.
struct GlfwLibrary {
  GlfwLibrary() {
    if (!glfwInit())
      throw std::runtime_error("cannot open a window: GLFW found no display (set DISPLAY, or run under xvfb-run -a)");
    if (!glfwVulkanSupported()) {
      glfwTerminate();
      throw std::runtime_error("cannot open a window: GLFW found no Vulkan loader");
    }
  }
  ~GlfwLibrary() { glfwTerminate(); }
  GlfwLibrary(const GlfwLibrary&) = delete;
  GlfwLibrary& operator=(const GlfwLibrary&) = delete;
};

VulkanExtensions windowExtensions() {
  uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (!names) throw std::runtime_error("cannot open a window: Vulkan cannot present to this display");
  return {std::vector<const char*>(names, names + count), {VK_KHR_SWAPCHAIN_EXTENSION_NAME}};
}

// "N 'name' WxH": monitor `index` of the display, in words.
std::string monitorInWords(GLFWmonitor* monitor, int index) {
  std::string words = std::to_string(index);
  words += " '";
  words += glfwGetMonitorName(monitor);
  words += "'";
  if (const GLFWvidmode* mode = glfwGetVideoMode(monitor)) {
    words += ' ';
    words += std::to_string(mode->width);
    words += 'x';
    words += std::to_string(mode->height);
  }
  return words;
}

// The display's monitor `index`, or an error naming the ones there are when it is not one of them.
GLFWmonitor* monitorAt(int index) {
  int count = 0;
  GLFWmonitor** monitors = glfwGetMonitors(&count);
  if (index >= 0 && index < count) return monitors[index];
  std::string message = "--monitor ";
  message += std::to_string(index);
  message += ": the display has ";
  message += std::to_string(count);
  message += count == 1 ? " monitor" : " monitors";
  for (int k = 0; k < count; ++k) {
    message += k == 0 ? " (" : ", ";
    message += monitorInWords(monitors[k], k);
  }
  if (count > 0) message += ")";
  throw std::runtime_error(message);
}

// Mouse state for the orbiting camera.
struct Mouse {
  bool dragging = false;
  bool handHeld[2] = {false, false};
  double x = 0, y = 0;
};

}  // namespace

struct Window::Impl {
  GlfwLibrary glfw;
  std::shared_ptr<const VulkanContext> ctx;
  GLFWwindow* window = nullptr;
  vk::raii::SurfaceKHR surface{nullptr};
  vk::raii::SwapchainKHR swapchain{nullptr};
  std::vector<vk::Image> images;
  vk::Extent2D extent;
  vk::raii::Fence acquired{nullptr};
  OrbitCamera camera;
  Mouse mouse;
  GLFWmonitor* monitor = nullptr;  // for full screen
  bool fullscreen = false;
  std::array<int, 4> windowed{0, 0, 0, 0};  // x, y, width, height of the window before it went full screen
  bool resized = false;                     // the framebuffer changed size: the swapchain is made again
  // A picture blitted over the window after the frame was drawn and copied for the stream, so never in the stream:
  // its pixels waiting to be copied in, and the image the blit reads.
  struct Layer {
    int width = 0, height = 0;
    bool changed = false;
    DeviceBuffer pixels;
    DeviceImage image;
    bool uploaded = false;  // image holds pixels (in transfer-source layout)
  };
  Layer inset;    // the performer view (setInset), over the bottom right corner
  Layer overlay;  // the operator overlay (showMessage while operatorOverlay), across the top
  bool operatorOverlay = false;
  std::string overlayText;  // what the overlay layer holds, at overlayWidth pixels across
  uint32_t overlayWidth = 0;
  // The copies of each frame (captureFrames): a fixed-size image the output is scaled into, and its pixels.
  DeviceImage captureImage;
  DeviceBuffer captureBuffer;
  std::vector<uint8_t> capturedPixels;
  // A frame submitted and not yet shown (submit, showSubmitted): its renderer and the swapchain image it goes to.
  struct Pending {
    Renderer* renderer;
    uint32_t image;
  };
  std::optional<Pending> pending;
  WindowKeys keys;
  PointerListener pointer;  // empty: the mouse only moves the camera
  std::string message;      // the banner's text (showMessage), shown until messageUntil
  std::chrono::steady_clock::time_point messageUntil;

  Impl(const std::string& title, int width, int height, const std::string& device, const WindowPlacement& placement)
      : ctx(std::make_shared<const VulkanContext>(device, windowExtensions())), monitor(monitorAt(placement.monitor)) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window)
      throw std::runtime_error("cannot open a window of " + std::to_string(width) + "x" + std::to_string(height));
    if (placement.fullscreen) enterFullscreen();
    VkSurfaceKHR raw = VK_NULL_HANDLE;
    if (glfwCreateWindowSurface(static_cast<VkInstance>(*ctx->instance), window, nullptr, &raw) != VK_SUCCESS)
      throw std::runtime_error("cannot create a Vulkan surface for the window");
    surface = vk::raii::SurfaceKHR(ctx->instance, raw);
    if (!ctx->physical.getSurfaceSupportKHR(ctx->queueFamily(), *surface))
      throw std::runtime_error("the Vulkan device " + ctx->info().name + " cannot present to this window");
    acquired = vk::raii::Fence(ctx->device, vk::FenceCreateInfo());
    makeSwapchain();
    glfwSetWindowUserPointer(window, this);
    glfwSetKeyCallback(window, onKey);
    glfwSetMouseButtonCallback(window, onButton);
    glfwSetCursorPosCallback(window, onCursor);
    glfwSetScrollCallback(window, onScroll);
    glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) { of(w).resized = true; });
  }

  // Borderless over the monitor at its current video mode (so the monitor does not switch modes), the pointer
  // hidden: a projector shows the picture and nothing else.
  void enterFullscreen() {
    glfwGetWindowPos(window, &windowed[0], &windowed[1]);
    glfwGetWindowSize(window, &windowed[2], &windowed[3]);
    const GLFWvidmode* mode = glfwGetVideoMode(monitor);
    if (!mode) throw std::runtime_error("full screen: the monitor " + describeMonitor() + " reports no video mode");
    glfwSetWindowMonitor(window, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
    glfwSetInputMode(window, GLFW_CURSOR, GLFW_CURSOR_HIDDEN);
    fullscreen = true;
    resized = true;
  }
  void leaveFullscreen() {
    glfwSetWindowMonitor(window, nullptr, windowed[0], windowed[1], windowed[2], windowed[3], GLFW_DONT_CARE);
    glfwSetInputMode(window, GLFW_CURSOR, GLFW_CURSOR_NORMAL);
    fullscreen = false;
    resized = true;
  }
  [[nodiscard]] std::string describeMonitor() const {
    int count = 0, x = 0, y = 0;
    GLFWmonitor** monitors = glfwGetMonitors(&count);
    const int index = static_cast<int>(std::find(monitors, monitors + count, monitor) - monitors);
    glfwGetMonitorPos(monitor, &x, &y);
    std::string words = "monitor ";
    words += monitorInWords(monitor, index);
    words += " at ";
    words += std::to_string(x);
    words += ',';
    words += std::to_string(y);
    return words;
  }

  ~Impl() {
    if (pending) ctx->device.waitIdle();  // a frame still drawn into a swapchain image
    swapchain.clear();
    surface.clear();
    if (window) glfwDestroyWindow(window);
  }

  void makeSwapchain() {
    ctx->device.waitIdle();
    const auto caps = ctx->physical.getSurfaceCapabilitiesKHR(*surface);
    int w = 0, h = 0;
    glfwGetFramebufferSize(window, &w, &h);
    extent = caps.currentExtent.width != UINT32_MAX
                 ? caps.currentExtent
                 : vk::Extent2D(
                       std::clamp(static_cast<uint32_t>(w), caps.minImageExtent.width, caps.maxImageExtent.width),
                       std::clamp(static_cast<uint32_t>(h), caps.minImageExtent.height, caps.maxImageExtent.height));
    // The renderer's output is an sRGB image: an sRGB swapchain makes the blit decode and re-encode it
    // unchanged. A UNORM one would show the linear values (too dark): refuse it rather than show wrong colours.
    const auto formats = ctx->physical.getSurfaceFormatsKHR(*surface);
    auto format = std::find_if(formats.begin(), formats.end(), [](const auto& f) {
      return f.format == vk::Format::eB8G8R8A8Srgb || f.format == vk::Format::eR8G8B8A8Srgb;
    });
    if (format == formats.end()) throw std::runtime_error("the window offers no 8-bit sRGB colour format");
    if (!(caps.supportedUsageFlags & vk::ImageUsageFlagBits::eTransferDst))
      throw std::runtime_error("the window's images cannot be copied to");
    // Immediate when offered: the loop measures its own frame rate; FIFO (always offered) otherwise.
    const auto modes = ctx->physical.getSurfacePresentModesKHR(*surface);
    const bool immediate = std::find(modes.begin(), modes.end(), vk::PresentModeKHR::eImmediate) != modes.end();
    const uint32_t count =
        caps.maxImageCount == 0 ? caps.minImageCount + 1 : std::min(caps.minImageCount + 1, caps.maxImageCount);
    resized = false;
    vk::SwapchainCreateInfoKHR info(
        {}, *surface, count, format->format, format->colorSpace, extent, 1, vk::ImageUsageFlagBits::eTransferDst,
        vk::SharingMode::eExclusive, {}, caps.currentTransform, vk::CompositeAlphaFlagBitsKHR::eOpaque,
        immediate ? vk::PresentModeKHR::eImmediate : vk::PresentModeKHR::eFifo, true, *swapchain);
    swapchain = vk::raii::SwapchainKHR(ctx->device, info);
    images = swapchain.getImages();
  }

  static Impl& of(GLFWwindow* w) { return *static_cast<Impl*>(glfwGetWindowUserPointer(w)); }

  static void onKey(GLFWwindow* w, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    WindowKeys& k = of(w).keys;
    switch (key) {
      case GLFW_KEY_ESCAPE:
      case GLFW_KEY_Q:
        k.quit = true;
        break;
      case GLFW_KEY_R:
        k.reset = true;
        break;
      case GLFW_KEY_D:
        k.dip = true;
        break;
      case GLFW_KEY_B:
        k.burst = true;
        break;
      case GLFW_KEY_SPACE:
      case GLFW_KEY_P:
        k.pause = true;
        break;
      case GLFW_KEY_C:
        k.nextColouring = true;
        break;
      case GLFW_KEY_HOME:
        k.resetCamera = true;
        break;
      case GLFW_KEY_F:
        k.fullscreen = true;
        break;
      case GLFW_KEY_V:
        k.performerView = true;
        break;
      case GLFW_KEY_M:
        k.mirrorView = true;
        break;
      case GLFW_KEY_O:
        k.operatorOverlay = true;
        break;
      default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) k.preset = key - GLFW_KEY_0;
        break;
    }
  }
  static void onButton(GLFWwindow* w, int button, int action, int) {
    Impl& m = of(w);
    const bool down = action == GLFW_PRESS;
    if (!m.pointer.button) {
      if (button == GLFW_MOUSE_BUTTON_LEFT) m.mouse.dragging = down;
      return;
    }
    if (button == GLFW_MOUSE_BUTTON_MIDDLE) m.mouse.dragging = down;
    const int hand = button == GLFW_MOUSE_BUTTON_LEFT ? 0 : (button == GLFW_MOUSE_BUTTON_RIGHT ? 1 : -1);
    if (hand < 0) return;
    m.mouse.handHeld[hand] = down;
    m.pointer.button(hand, down);
  }
  static void onCursor(GLFWwindow* w, double x, double y) {
    Impl& m = of(w);
    if (m.pointer.moved) {
      int width = 1, height = 1;
      glfwGetWindowSize(w, &width, &height);
      m.pointer.moved(x / std::max(width, 1), y / std::max(height, 1));
    }
    if (m.mouse.dragging) {
      m.camera.yaw -= 0.005f * static_cast<float>(x - m.mouse.x);
      m.camera.pitch = std::clamp(m.camera.pitch + 0.005f * static_cast<float>(y - m.mouse.y), -1.4f, 1.4f);
      m.keys.cameraMoved = true;
    }
    m.mouse.x = x;
    m.mouse.y = y;
  }
  static void onScroll(GLFWwindow* w, double, double dy) {
    Impl& m = of(w);
    if (m.pointer.push && (m.mouse.handHeld[0] || m.mouse.handHeld[1])) {
      m.pointer.push(dy);
      return;
    }
    OrbitCamera& c = m.camera;
    c.distance = std::clamp(c.distance * std::pow(0.9f, static_cast<float>(dy)), 0.3f, 30.0f);
    m.keys.cameraMoved = true;
  }

  // Waits for the next swapchain image; recreates the swapchain when the window changed.
  uint32_t acquire() {
    if (resized) makeSwapchain();
    for (;;) {
      try {
        const auto [result, index] = swapchain.acquireNextImage(UINT64_MAX, nullptr, *acquired);
        if (ctx->device.waitForFences({*acquired}, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
          throw std::runtime_error("Vulkan: waiting for a window image failed");
        ctx->device.resetFences({*acquired});
        return index;
      } catch (const vk::OutOfDateKHRError&) {
        makeSwapchain();
      }
    }
  }

  // Copies the renderer's output into swapchain image `index`, scaled to the window, ready to present.
  void recordBlit(const vk::raii::CommandBuffer& cb, vk::Image output, vk::Extent2D from, uint32_t index) {
    using Stage = vk::PipelineStageFlagBits;
    using Access = vk::AccessFlagBits;
    const vk::Image target = images[index];
    transitionImage(cb, target, vk::ImageLayout::eUndefined, vk::ImageLayout::eTransferDstOptimal, Stage::eTransfer, {},
                    Stage::eTransfer, Access::eTransferWrite);
    const vk::ImageSubresourceLayers colour(vk::ImageAspectFlagBits::eColor, 0, 0, 1);
    const std::array<vk::Offset3D, 2> src{
        vk::Offset3D(0, 0, 0), vk::Offset3D(static_cast<int32_t>(from.width), static_cast<int32_t>(from.height), 1)};
    const std::array<vk::Offset3D, 2> dst{vk::Offset3D(0, 0, 0), vk::Offset3D(static_cast<int32_t>(extent.width),
                                                                              static_cast<int32_t>(extent.height), 1)};
    cb.blitImage(output, vk::ImageLayout::eTransferSrcOptimal, target, vk::ImageLayout::eTransferDstOptimal,
                 vk::ImageBlit(colour, src, colour, dst), vk::Filter::eLinear);
    if (inset.uploaded) recordLayer(cb, target, inset, insetRectangle());
    if (overlay.uploaded && operatorOverlay) recordLayer(cb, target, overlay, overlayRectangle());
    transitionImage(cb, target, vk::ImageLayout::eTransferDstOptimal, vk::ImageLayout::ePresentSrcKHR, Stage::eTransfer,
                    Access::eTransferWrite, Stage::eBottomOfPipe, {});
    if (captureBuffer.size() > 0) recordCapture(cb, output, from);
  }

  // A layer's new pixels into its image (when they changed), then the image over `rectangle` of `target`, which the
  // main blit wrote before: a barrier orders the two writes.
  static void recordLayer(const vk::raii::CommandBuffer& cb, vk::Image target, Layer& layer,
                          const std::array<int32_t, 4>& rectangle) {
    using Stage = vk::PipelineStageFlagBits;
    using Access = vk::AccessFlagBits;
    using Layout = vk::ImageLayout;
    if (layer.changed) {
      transitionImage(cb, layer.image.handle(), Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eTransfer,
                      Access::eTransferRead, Stage::eTransfer, Access::eTransferWrite);
      cb.copyBufferToImage(layer.pixels.handle(), layer.image.handle(), Layout::eTransferDstOptimal,
                           vk::BufferImageCopy(0, 0, 0, {vk::ImageAspectFlagBits::eColor, 0, 0, 1}, {0, 0, 0},
                                               vk::Extent3D(layer.image.extent(), 1)));
      transitionImage(cb, layer.image.handle(), Layout::eTransferDstOptimal, Layout::eTransferSrcOptimal,
                      Stage::eTransfer, Access::eTransferWrite, Stage::eTransfer, Access::eTransferRead);
      layer.changed = false;
    }
    const vk::MemoryBarrier afterBlit(Access::eTransferWrite, Access::eTransferWrite);
    cb.pipelineBarrier(Stage::eTransfer, Stage::eTransfer, {}, afterBlit, {}, {});
    const auto [x0, y0, x1, y1] = rectangle;
    const vk::ImageSubresourceLayers colour(vk::ImageAspectFlagBits::eColor, 0, 0, 1);
    const std::array<vk::Offset3D, 2> src{vk::Offset3D(0, 0, 0), vk::Offset3D(layer.width, layer.height, 1)};
    const std::array<vk::Offset3D, 2> dst{vk::Offset3D(x0, y0, 0), vk::Offset3D(x1, y1, 1)};
    cb.blitImage(layer.image.handle(), Layout::eTransferSrcOptimal, target, Layout::eTransferDstOptimal,
                 vk::ImageBlit(colour, src, colour, dst), vk::Filter::eLinear);
  }
  // Where the inset goes: kInsetWidth of the window's width, its own aspect, a margin from the bottom right corner.
  [[nodiscard]] std::array<int32_t, 4> insetRectangle() const {
    const auto w = static_cast<int32_t>(Window::kInsetWidth * extent.width);
    const auto h = static_cast<int32_t>(static_cast<double>(w) * inset.height / std::max(inset.width, 1));
    const int32_t margin = std::max<int32_t>(4, static_cast<int32_t>(extent.height) / 60);
    const auto x1 = static_cast<int32_t>(extent.width) - margin, y1 = static_cast<int32_t>(extent.height) - margin;
    return {std::max(0, x1 - w), std::max(0, y1 - h), x1, y1};
  }
  // Where the operator overlay goes: across the top of the window, at its own size.
  [[nodiscard]] std::array<int32_t, 4> overlayRectangle() const {
    return {0, 0, overlay.width, std::min(overlay.height, static_cast<int32_t>(extent.height))};
  }

  // A layer's pixels (RGBA, rows from the top) for the next present: a new image when the size changed.
  void setLayer(Layer& layer, int width, int height, const std::vector<uint8_t>& rgba) {
    if (width != layer.width || height != layer.height || layer.pixels.size() == 0) {
      ctx->device.waitIdle();  // the old image may still be read by a frame in flight
      const vk::Extent2D size(static_cast<uint32_t>(width), static_cast<uint32_t>(height));
      layer.image = DeviceImage(*ctx, size, vk::Format::eR8G8B8A8Srgb,
                                vk::ImageUsageFlagBits::eTransferDst | vk::ImageUsageFlagBits::eTransferSrc);
      layer.pixels = DeviceBuffer(*ctx, 4ull * width * height, DeviceBuffer::Placement::Host);
      layer.width = width;
      layer.height = height;
    }
    layer.pixels.write(rgba.data(), rgba.size());  // present() waits for its frame: nothing reads it now
    layer.changed = true;
    layer.uploaded = true;
  }

  // The overlay layer for the message shown now (the banner at the window's width), drawn again only when the
  // message or the width changed.
  void updateOverlay() {
    const bool shown = std::chrono::steady_clock::now() < messageUntil;
    const std::string text = shown ? message : std::string();
    if (text == overlayText && extent.width == overlayWidth) return;
    overlayText = text;
    overlayWidth = extent.width;
    const BannerImage banner = drawBanner(text, static_cast<int>(extent.width), static_cast<int>(extent.height));
    if (banner.height == 0) {
      overlay.uploaded = false;
      return;
    }
    setLayer(overlay, banner.width, banner.height, banner.rgba);
  }

  // The output scaled into the capture image, and that copied to the capture buffer for the host to read.
  void recordCapture(const vk::raii::CommandBuffer& cb, vk::Image output, vk::Extent2D from) const {
    using Stage = vk::PipelineStageFlagBits;
    using Access = vk::AccessFlagBits;
    using Layout = vk::ImageLayout;
    const vk::Extent2D size = captureImage.extent();
    transitionImage(cb, captureImage.handle(), Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eTransfer,
                    Access::eTransferRead, Stage::eTransfer, Access::eTransferWrite);
    const vk::ImageSubresourceLayers colour(vk::ImageAspectFlagBits::eColor, 0, 0, 1);
    const std::array<vk::Offset3D, 2> src{
        vk::Offset3D(0, 0, 0), vk::Offset3D(static_cast<int32_t>(from.width), static_cast<int32_t>(from.height), 1)};
    const std::array<vk::Offset3D, 2> dst{
        vk::Offset3D(0, 0, 0), vk::Offset3D(static_cast<int32_t>(size.width), static_cast<int32_t>(size.height), 1)};
    cb.blitImage(output, Layout::eTransferSrcOptimal, captureImage.handle(), Layout::eTransferDstOptimal,
                 vk::ImageBlit(colour, src, colour, dst), vk::Filter::eLinear);
    transitionImage(cb, captureImage.handle(), Layout::eTransferDstOptimal, Layout::eTransferSrcOptimal,
                    Stage::eTransfer, Access::eTransferWrite, Stage::eTransfer, Access::eTransferRead);
    cb.copyImageToBuffer(
        captureImage.handle(), Layout::eTransferSrcOptimal, captureBuffer.handle(),
        vk::BufferImageCopy(0, 0, 0, {vk::ImageAspectFlagBits::eColor, 0, 0, 1}, {0, 0, 0}, vk::Extent3D(size, 1)));
    const vk::MemoryBarrier toHost(Access::eTransferWrite, Access::eHostRead);
    cb.pipelineBarrier(Stage::eTransfer, Stage::eHost, {}, toHost, {}, {});
  }
};

Window::Window(const std::string& title, int width, int height, const std::string& device,
               const WindowPlacement& placement)
    : impl_(std::make_unique<Impl>(title, width, height, device, placement)) {}

Window::~Window() = default;

std::shared_ptr<const VulkanContext> Window::context() const { return impl_->ctx; }
OrbitCamera& Window::camera() { return impl_->camera; }

void Window::setPointerListener(PointerListener listener) { impl_->pointer = std::move(listener); }

WindowKeys Window::poll() {
  Impl& m = *impl_;
  glfwPollEvents();
  WindowKeys keys = m.keys;
  m.keys = {};
  if (glfwWindowShouldClose(m.window)) keys.quit = true;
  return keys;
}

void Window::setFullscreen(bool on) {
  if (on == impl_->fullscreen) return;
  showSubmitted();  // into the swapchain it was drawn for
  if (on)
    impl_->enterFullscreen();
  else
    impl_->leaveFullscreen();
  glfwPollEvents();
  impl_->makeSwapchain();
}

bool Window::fullscreen() const { return impl_->fullscreen; }
std::string Window::monitorDescription() const { return impl_->describeMonitor(); }
std::array<int, 2> Window::size() const {
  return {static_cast<int>(impl_->extent.width), static_cast<int>(impl_->extent.height)};
}

void Window::setInset(int width, int height, const std::vector<uint8_t>& rgb) {
  showSubmitted();  // its blit reads the layer's pixels
  Impl& m = *impl_;
  if (rgb.empty() || width <= 0 || height <= 0) {
    m.inset.uploaded = false;
    return;
  }
  if (rgb.size() != 3ull * static_cast<size_t>(width) * static_cast<size_t>(height))
    throw std::invalid_argument("Window::setInset: " + std::to_string(rgb.size()) + " bytes for " +
                                std::to_string(width) + "x" + std::to_string(height) + " RGB");
  std::vector<uint8_t> rgba(4ull * width * height, 255);
  for (size_t i = 0; i < static_cast<size_t>(width) * static_cast<size_t>(height); ++i)
    for (size_t c = 0; c < 3; ++c) rgba[4 * i + c] = rgb[3 * i + c];
  m.setLayer(m.inset, width, height, rgba);
}

void Window::setOperatorOverlay(bool on) { impl_->operatorOverlay = on; }

bool Window::operatorOverlay() const { return impl_->operatorOverlay; }

void Window::captureFrames(int width, int height) {
  showSubmitted();  // its blit writes the copy
  Impl& m = *impl_;
  m.ctx->device.waitIdle();
  m.captureBuffer = DeviceBuffer();
  m.captureImage = DeviceImage();
  m.capturedPixels.clear();
  if (width <= 0 || height <= 0) return;
  const vk::Extent2D extent(static_cast<uint32_t>(width), static_cast<uint32_t>(height));
  m.captureImage = DeviceImage(*m.ctx, extent, vk::Format::eR8G8B8A8Srgb,
                               vk::ImageUsageFlagBits::eTransferDst | vk::ImageUsageFlagBits::eTransferSrc);
  m.captureBuffer = DeviceBuffer(*m.ctx, 4ull * width * height, DeviceBuffer::Placement::Readback);
}

const std::vector<uint8_t>& Window::captured() const { return impl_->capturedPixels; }

void Window::setTitle(const std::string& title) { glfwSetWindowTitle(impl_->window, title.c_str()); }

void Window::showMessage(const std::string& line, double seconds) {
  const double shownFor = seconds > 0 ? std::min(seconds, 1e6) : 0.0;  // NaN or negative: not shown
  impl_->message = line;
  impl_->messageUntil =
      std::chrono::steady_clock::now() +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(shownFor));
}

void Window::present(Renderer& renderer, RenderFrame frame) {
  submit(renderer, std::move(frame));
  showSubmitted();
}

void Window::submit(Renderer& renderer, RenderFrame frame) {
  showSubmitted();
  Impl& m = *impl_;
  const uint32_t index = m.acquire();
  if (m.operatorOverlay) m.updateOverlay();
  const vk::Extent2D from(static_cast<uint32_t>(renderer.options().width),
                          static_cast<uint32_t>(renderer.options().height));
  renderer.submit(frame, false,
                  [&](const vk::raii::CommandBuffer& cb, vk::Image output) { m.recordBlit(cb, output, from, index); });
  m.pending = Impl::Pending{&renderer, index};
}

bool Window::showSubmitted() {
  Impl& m = *impl_;
  if (!m.pending) return false;
  const Impl::Pending shown = *std::exchange(m.pending, std::nullopt);
  shown.renderer->wait();
  if (m.captureBuffer.size() > 0) {  // the frame's copy is there
    m.capturedPixels.resize(m.captureBuffer.size());
    m.captureBuffer.read(m.capturedPixels.data(), m.capturedPixels.size());
  }
  try {
    const vk::SwapchainKHR chain = *m.swapchain;
    (void)m.ctx->queue.presentKHR(vk::PresentInfoKHR({}, chain, shown.image));
  } catch (const vk::OutOfDateKHRError&) {
    m.makeSwapchain();
  }
  return true;
}

}  // namespace gb
