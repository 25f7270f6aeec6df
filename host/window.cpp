#include "window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "device_image.h"

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
  OrbitCamera camera, initialCamera;
  Mouse mouse;
  WindowKeys keys;
  PointerListener pointer;  // empty: the mouse only moves the camera
  std::string message;      // the banner's text (showMessage), shown until messageUntil
  std::chrono::steady_clock::time_point messageUntil;

  Impl(const std::string& title, int width, int height, const std::string& device)
      : ctx(std::make_shared<const VulkanContext>(device, windowExtensions())) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window)
      throw std::runtime_error("cannot open a window of " + std::to_string(width) + "x" + std::to_string(height));
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
  }

  ~Impl() {
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
      default:
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
  }

  // Waits for the next swapchain image; recreates the swapchain when the window changed.
  uint32_t acquire() {
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
  void recordBlit(const vk::raii::CommandBuffer& cb, vk::Image output, vk::Extent2D from, uint32_t index) const {
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
    transitionImage(cb, target, vk::ImageLayout::eTransferDstOptimal, vk::ImageLayout::ePresentSrcKHR, Stage::eTransfer,
                    Access::eTransferWrite, Stage::eBottomOfPipe, {});
  }
};

Window::Window(const std::string& title, int width, int height, const std::string& device)
    : impl_(std::make_unique<Impl>(title, width, height, device)) {}

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
  if (keys.resetCamera) m.camera = m.initialCamera;
  return keys;
}

void Window::setTitle(const std::string& title) { glfwSetWindowTitle(impl_->window, title.c_str()); }

void Window::showMessage(const std::string& line, double seconds) {
  const double shownFor = seconds > 0 ? std::min(seconds, 1e6) : 0.0;  // NaN or negative: not shown
  impl_->message = line;
  impl_->messageUntil =
      std::chrono::steady_clock::now() +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(shownFor));
}

void Window::present(Renderer& renderer, RenderFrame frame) {
  Impl& m = *impl_;
  const uint32_t index = m.acquire();
  frame.camera = m.camera;
  if (frame.banner.empty() && std::chrono::steady_clock::now() < m.messageUntil) frame.banner = m.message;
  const vk::Extent2D from(static_cast<uint32_t>(renderer.options().width),
                          static_cast<uint32_t>(renderer.options().height));
  renderer.render(frame, false,
                  [&](const vk::raii::CommandBuffer& cb, vk::Image output) { m.recordBlit(cb, output, from, index); });
  try {
    const vk::SwapchainKHR chain = *m.swapchain;
    (void)m.ctx->queue.presentKHR(vk::PresentInfoKHR({}, chain, index));
  } catch (const vk::OutOfDateKHRError&) {
    m.makeSwapchain();
  }
}

}  // namespace gb
