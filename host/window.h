#pragma once
// The live window (GLFW on X11): a Vulkan swapchain that shows the renderer's output, an orbiting camera on the
// mouse (drag to turn, wheel to zoom) and the keys of `giantbubble view` (app/view_command.cpp). It runs under
// Xvfb with lavapipe, which is how CI tests it.

#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "render_scene.h"
#include "renderer.h"
#include "vulkan_context.h"

struct GLFWwindow;

namespace gb {

// Keys pressed since the last poll.
struct WindowKeys {
  bool quit = false;           // Escape, Q, or the window closed
  bool reset = false;          // R: new film and the performance from its start
  bool dip = false;            // D: dip the wands again (new film where the wands are)
  bool burst = false;          // B: poke the film
  bool pause = false;          // Space or P: pause / resume the simulation
  bool nextColouring = false;  // C: interference -> thickness -> air flow
  bool resetCamera = false;    // Home
};

// Where the mouse's hand input goes when the wands follow the mouse (`giantbubble live --input mouse`): the
// left and right buttons drag the left and right hands, the wheel with a button held pushes them forward or
// back; the camera then orbits with the middle button, and the wheel alone still zooms.
struct PointerListener {
  std::function<void(double x, double y)> moved;    // pointer in window coordinates 0..1, origin top left
  std::function<void(int hand, bool down)> button;  // hand 0 left, 1 right
  std::function<void(double notches)> push;         // wheel notches while a hand is held
};

class Window {
 public:
  // Opens a window and a Vulkan device that can present to it (`device` as for VulkanContext). Throws with the
  // reason when there is no display or no such device.
  Window(const std::string& title, int width, int height, const std::string& device);
  ~Window();
  Window(const Window&) = delete;  // owns the window and the swapchain
  Window& operator=(const Window&) = delete;

  [[nodiscard]] std::shared_ptr<const VulkanContext> context() const;
  // Handles window events: returns the keys pressed and moves the camera with the mouse.
  WindowKeys poll();
  [[nodiscard]] OrbitCamera& camera();
  // Hands the left and right buttons and the wheel (with a button held) to `listener` (see PointerListener).
  void setPointerListener(PointerListener listener);
  // Renders `frame` and shows it (the renderer's image scaled to the window). Waits until it is presented.
  void present(Renderer& renderer, RenderFrame frame);
  // The title bar's text (the live show's figures).
  void setTitle(const std::string& title);
  // A status line for the audience and the operator (a recovery, a lost camera, nobody in front of it), shown
  // in a banner over the top of the image for `seconds` of wall time; a later message replaces it, and an empty
  // one removes it. The title bar alone is not enough: a show runs full screen or on a projector.
  void showMessage(const std::string& line, double seconds = kMessageSeconds);
  static constexpr double kMessageSeconds = 5.0;  // long enough to read two lines from across a room

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gb
