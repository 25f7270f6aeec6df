#pragma once
// The live window (GLFW on X11): a Vulkan swapchain that shows the renderer's output, an orbiting camera on the
// mouse (drag to turn, wheel to zoom) and the keys of `giantbubble view` (app/show/live_show.cpp); full screen on a
// chosen monitor (a projector), a picture-in-picture inset (the performer view), the operator overlay (messages for
// whoever runs the show) and a copy of each frame at a fixed size (the video stream), which holds neither of them. It
// runs under Xvfb with lavapipe, which is how CI tests it.

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "host/render_scene.h"
#include "host/renderer.h"
#include "host/vulkan_context.h"

struct GLFWwindow;

namespace gb {

// Keys pressed since the last poll.
struct WindowKeys {
  bool quit = false;             // Escape, Q, or the window closed
  bool reset = false;            // R: new film and the performance from its start
  bool dip = false;              // D: dip the wands again (new film where the wands are)
  bool burst = false;            // B: poke the film
  bool pause = false;            // Space or P: pause / resume the simulation
  bool nextColouring = false;    // C: interference -> thickness -> air flow
  bool resetCamera = false;      // Home
  bool fullscreen = false;       // F: full screen <-> window
  bool performerView = false;    // V: the performer view on or off
  bool operatorOverlay = false;  // O: the operator overlay on or off
  bool mirrorView = false;       // M: the mirror view on or off
  int preset = 0;                // 1..9: a digit key, the saved preset of that number (live's presets); 0: none
  bool cameraMoved = false;      // the mouse turned or zoomed camera() (a drag, the wheel)
};

// Where the window goes: a window of the given size, or borderless over a whole monitor at its own resolution.
struct WindowPlacement {
  bool fullscreen = false;  // full screen on `monitor` from the start (F toggles)
  int monitor = 0;          // index in the display's list of monitors (0: the primary)
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
  // reason when there is no display, no such monitor (naming the ones there are) or no such device.
  Window(const std::string& title, int width, int height, const std::string& device,
         const WindowPlacement& placement = {});
  ~Window();
  Window(const Window&) = delete;  // owns the window and the swapchain
  Window& operator=(const Window&) = delete;

  [[nodiscard]] std::shared_ptr<const VulkanContext> context() const;
  // Handles window events: returns the keys pressed and moves camera() with the mouse (WindowKeys::cameraMoved).
  WindowKeys poll();
  // The camera the mouse turns and zooms; the caller draws with it or with its own (a camera following the film).
  [[nodiscard]] OrbitCamera& camera();
  // Hands the left and right buttons and the wheel (with a button held) to `listener` (see PointerListener).
  void setPointerListener(PointerListener listener);
  // Renders `frame` (with its own camera) and shows it: the renderer's image scaled to the window, the inset over
  // its bottom right corner. Waits until it is presented.
  void present(Renderer& renderer, RenderFrame frame);
  // present() in two halves, so that the caller may simulate the next frame while the device draws this one:
  // submit() starts drawing `frame` (everything it points to is copied first, Renderer::submit) after showing a frame
  // still pending; showSubmitted() waits for it and shows it (false when none is pending). A pending frame is shown
  // first by whatever changes what the window draws into (present, setFullscreen, setInset, captureFrames).
  void submit(Renderer& renderer, RenderFrame frame);
  bool showSubmitted();

  // Full screen: borderless over the placement's monitor at its own resolution (no change of video mode), or back
  // to the window as it was. The swapchain follows at once; size() says its new size.
  void setFullscreen(bool on);
  [[nodiscard]] bool fullscreen() const;
  // The monitor used for full screen, in words ("monitor 0 'HDMI-1' 1920x1080 at 0,0").
  [[nodiscard]] std::string monitorDescription() const;
  // The pixels presented: the swapchain's width and height.
  [[nodiscard]] std::array<int, 2> size() const;

  // A picture-in-picture over the bottom right corner of what is shown, kInsetWidth of the window's width, from
  // the next present on: width x height RGB 8-bit (sRGB), rows from the top. Empty `rgb`: none.
  void setInset(int width, int height, const std::vector<uint8_t>& rgb);
  static constexpr double kInsetWidth = 0.3;

  // From the next present on, each frame drawn (without the inset) is also scaled to width x height and kept:
  // captured() gives it as RGBA 8-bit (sRGB), rows from the top. 0 x 0: no copies.
  void captureFrames(int width, int height);
  [[nodiscard]] const std::vector<uint8_t>& captured() const;
  // The title bar's text (the live show's figures).
  void setTitle(const std::string& title);
  // A status line for the operator (a recovery, a lost camera, nobody in front of it), shown in a banner over the
  // top of the window for `seconds` of wall time while the operator overlay is on; a later message replaces it, and
  // an empty one removes it. The title bar alone is not enough: a show runs full screen or on a projector. The
  // overlay is drawn after the frame is copied for the stream, so neither the stream nor (with the overlay off, the
  // default) the audience's picture ever shows it.
  void showMessage(const std::string& line, double seconds = kMessageSeconds);
  void setOperatorOverlay(bool on);
  [[nodiscard]] bool operatorOverlay() const;
  static constexpr double kMessageSeconds = 5.0;  // long enough to read two lines from across a room

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gb
