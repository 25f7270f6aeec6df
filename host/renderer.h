#pragma once
// The renderer (Section 8 of the paper): the film as a two-sided transparent sheet coloured by thin-film
// interference (host/thin_film.h's lookup table) reflecting an environment and dimming what is behind it,
// over the floor, the wands and their string and the aerosol droplets; or coloured by a diagnostic
// (thickness, air flow). Three passes into offscreen images, then the caller reads the pixels (PNG, video) or
// copies the image to a window (host/window.h):
//   1. opaque:   floor, wands, string, droplets                    -> colour (RGBA16F) + depth
//   2. film:     weighted blended order-independent transparency    -> accum (RGBA16F) + reveal (R16F)
//   3. resolve:  film over opaque (or the environment where nothing opaque is), exposure, sRGB encoding
//                                                                    -> output (RGBA8)
// docs/rendering.md has the optics and the choices.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bursting.h"
#include "device_film.h"
#include "film.h"
#include "render_scene.h"
#include "vulkan_context.h"

namespace gb {

enum class Colouring { Interference, Thickness, AirFlow };
Colouring colouringFromName(const std::string& name);  // "interference", "thickness", "airflow"; throws
const char* colouringName(Colouring colouring);

struct RenderOptions {
  int width = 1280;                           // pixels
  int height = 720;
  Colouring colouring = Colouring::Interference;
  float thickColour = 7e-6f;                  // thickness drawn red by the thickness colouring (m), as app/ images
  float airFlowColour = 0.1f;                 // air flow strength drawn yellow (m^3/s): the default stroke peaks at 0.08
  float exposure = 1.0f;                      // radiance scale before display encoding
  float dropletRadius = 0.004f;               // drawn size of an aerosol droplet (m)
};

// One frame to draw. Everything but the film is optional.
struct RenderFrame {
  const Film* film = nullptr;
  const DeviceFilm* deviceFilm = nullptr;  // the Vulkan stepper's buffers on the renderer's device: read in
                                           // place; null: the film's state is uploaded from the host
  const Aerosol* aerosol = nullptr;
  float aerosolLifetime = 1.0f;            // s, for the droplets' fade
  const WireFrame* wireFrame = nullptr;    // the wands and their string (or ring)
  OrbitCamera camera;
};

class Renderer {
 public:
  // `environment`: what the film reflects and what is seen behind it (studioEnvironment() or a user image).
  Renderer(std::shared_ptr<const VulkanContext> context, const RenderOptions& options,
           const EnvironmentImage& environment);
  ~Renderer();
  Renderer(const Renderer&) = delete;  // owns device objects
  Renderer& operator=(const Renderer&) = delete;

  // Draws a frame and waits for it. `readback`: also copy the pixels for readPixels(). `after` records more
  // commands into the same submission once the output image is in transfer-source layout (the window's blit).
  using AfterRender = std::function<void(const vk::raii::CommandBuffer&, vk::Image output)>;
  void render(const RenderFrame& frame, bool readback = true, const AfterRender& after = {});
  // The last frame read back, RGB 8 bits per channel (sRGB), rows from the top.
  [[nodiscard]] std::vector<uint8_t> readPixels() const;

  void setColouring(Colouring colouring);
  [[nodiscard]] const RenderOptions& options() const;
  [[nodiscard]] const VulkanContext& context() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gb
