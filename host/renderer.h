#pragma once
// The renderer (Section 8 of the paper): the film as a two-sided transparent sheet coloured by thin-film
// interference (host/thin_film.h's lookup table) reflecting an environment and dimming what is behind it,
// over the ground, the wands and their string, the rim of a bursting hole and the aerosol droplets; or coloured
// by a diagnostic (thickness, air flow). Passes into offscreen images, multisampled (MSAA) and resolved, then the
// caller reads the pixels (PNG, video) or copies the image to a window (host/window.h):
//   1. opaque:   ground, wands, string, hole rims, and in the mirror view the camera's image at its own depth
//                (host/camera_layer.h)                              -> colour (RGBA16F) + depth
//   2. film:     film and droplets, weighted blended order-independent transparency
//                                                                    -> accum (RGBA16F) + reveal (R16F)
//   3. sky:      the environment along each pixel's view ray, only when the view has turned or zoomed
//                                                                    -> sky (RGBA16F), kept between frames
//   4. resolve:  film over opaque (or the sky where nothing opaque is), exposure, sRGB encoding
//                                                                    -> output (RGBA8)
// docs/rendering.md has the optics and the choices.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "host/camera_layer.h"
#include "host/device_film.h"
#include "host/render_scene.h"
#include "host/vulkan_context.h"
#include "model/film.h"
#include "topology/bursting.h"

namespace gb {

enum class Colouring { Interference, Thickness, AirFlow };
Colouring colouringFromName(const std::string& name);  // "interference", "thickness", "airflow"; throws
const char* colouringName(Colouring colouring);

struct RenderOptions {
  int width = 1280;  // pixels
  int height = 720;
  Colouring colouring = Colouring::Interference;
  float thickColour = 7e-6f;        // thickness drawn red by the thickness colouring (m), as app/ images
  float airFlowColour = 0.1f;       // air flow strength drawn yellow (m^3/s): the default stroke peaks at 0.08
  float exposure = 1.0f;            // radiance scale before display encoding
  float dropletRadius = 0.003f;     // drawn size of an aerosol droplet (m)
  float minTubePixels = 0.6f;       // the string, wands and rims are drawn at least this radius (pixels):
                                    // a 4 mm string far away would otherwise break into dashes that
                                    // no sample pattern can join
  int samples = 4;                  // multisample anti-aliasing: samples per pixel (the most the device
                                    // supports up to this; 1: none)
  float thicknessVariation = 0.0f;  // sigma of drawn sub-particle thickness swirls (host/film_swirls.h), interference
                                    // colouring only; 0 (default): the simulated thickness (film flow) as it is
};

// The largest image side the renderer draws (pixels), whatever the device allows.
inline constexpr int kMaxRenderSide = 16384;
// The memory a width x height image takes at `samples` per pixel (bytes): its colour and depth targets, the
// multisampled ones, the output and the two frames' read-back rows (16384 x 16384 is 11 GB at 1 sample).
double renderTargetBytes(int width, int height, int samples);
// Why `device` cannot draw a width x height image at `samples` per pixel, or empty when it can: a side beyond its
// largest (and kMaxRenderSide), or targets beyond a quarter of its largest memory heap, which would fail mid-show
// instead of at the start. Names --width and --height.
std::string renderSizeProblem(int width, int height, int samples, int largestSide, double heapBytes,
                              const std::string& device);

// One frame to draw. Everything but the film is optional.
struct RenderFrame {
  // The film's topology, and its state: uploaded whole without deviceFilm; with it, the positions of the hole rims
  // and, for the drawn swirls (thicknessVariation), which particles are new are read from it.
  const Film* film = nullptr;
  const DeviceFilm* deviceFilm = nullptr;  // the Vulkan stepper's buffers on the renderer's device: copied there,
                                           // never through the host; null: the film's state is uploaded
  const Aerosol* aerosol = nullptr;
  float aerosolLifetime = 1.0f;                            // s, for the droplets' fade
  float blackFilmThickness = Params{}.blackFilmThickness;  // m: thinner film is drawn as black film
  const WireFrame* wireFrame = nullptr;                    // the wands and their string (or ring)
  OrbitCamera camera;
  // The mirror view (host/camera_layer.h): seen from the depth camera instead of `camera`, with what it saw
  // (`cameraImage`, in the camera's pixels; null: nothing of it) drawn in at its own depth.
  const DepthCameraView* mirror = nullptr;
  const CameraImage* cameraImage = nullptr;
};

class Renderer {
 public:
  // `environment`: what the film reflects and what is seen behind it (skyEnvironment(), studioEnvironment() or a
  // user image).
  Renderer(std::shared_ptr<const VulkanContext> context, const RenderOptions& options,
           const EnvironmentImage& environment);
  ~Renderer();
  Renderer(const Renderer&) = delete;  // owns device objects
  Renderer& operator=(const Renderer&) = delete;

  // Draws a frame and waits for it. `readback`: also copy the pixels for readPixels(). `after` records more
  // commands into the same submission once the output image is in transfer-source layout (the window's blit).
  using AfterRender = std::function<void(const vk::raii::CommandBuffer&, vk::Image output)>;
  void render(const RenderFrame& frame, bool readback = true, const AfterRender& after = {});
  // The same without waiting: everything `frame` points to is copied before it returns, so the caller may change it
  // (simulate the next frame) while the device draws. A film on the device (`frame.deviceFilm`) is copied there into
  // the frame's own buffers, and submit waits for that copy alone. Two frames may be in flight: the one submitted two
  // calls before is waited for first. Returns the frame's ticket, for readPixels.
  using Ticket = uint64_t;
  Ticket submit(const RenderFrame& frame, bool readback = true, const AfterRender& after = {});
  void wait();  // for every frame submitted
  // When the device drew each frame waited for since the last call, the latest 1024 at most (its first command to
  // its last, the window's blit included), in seconds of the host's steady clock (std::chrono::steady_clock), oldest
  // first: `run` tells from them how much of its step the drawing overlapped. Empty on a device whose timestamps the
  // host cannot read (VulkanContext::timestampsOnHostClock).
  using BusyInterval = DeviceBusyInterval;
  [[nodiscard]] std::vector<BusyInterval> takeDrawnIntervals();
  // A frame read back, RGB 8 bits per channel (sRGB), rows from the top; waits for it. The last frame submitted,
  // or the one of `frame`'s ticket, which must be one of the last two submitted (std::logic_error otherwise).
  [[nodiscard]] std::vector<uint8_t> readPixels();
  [[nodiscard]] std::vector<uint8_t> readPixels(Ticket frame);

  // Draws at a new size from the next frame on (the live window's dynamic resolution: its blit scales the image
  // to the window). The targets and pipelines are made again; the film's swirls and the textures are kept.
  // Throws std::invalid_argument outside 16..16384 pixels, as the constructor does.
  void resize(int width, int height);
  void setColouring(Colouring colouring);
  [[nodiscard]] const RenderOptions& options() const;
  [[nodiscard]] const VulkanContext& context() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gb
