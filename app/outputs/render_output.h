#pragma once
// Rendered pictures of a run (`giantbubble run --render`): PNG frames beside the meshes and stats, and an MP4
// through an ffmpeg pipe when ffmpeg is installed. The renderer (host/renderer.h) shares the Vulkan stepper's
// device and copies the film from its buffers there; with the CPU backend it takes a Vulkan device of its own
// (lavapipe without a GPU) and uploads the film each frame.

#include <cstdio>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "capture/output_file.h"
#include "host/renderer.h"
#include "scene/run_options.h"
#include "simulation/simulation.h"

namespace CLI {
class App;
}

namespace gb {

// Whether a command writes rendered files: `run` does (PNG frames and the video); `live` draws into its window only,
// and refuses --render, --render-every and --video by name rather than take them and write nothing.
enum class RenderedFiles { Written, None };

// Adds --width, --height, --colouring, --environment, --camera, --samples to a command, and --render, --render-every
// and --video where it writes rendered files.
void addRenderOptions(CLI::App& command, RenderOutputOptions& options, RenderedFiles files = RenderedFiles::Written);

// The MSAA samples per pixel to draw with on `device` (its VulkanContext type, "CPU" for lavapipe): --samples when
// given; else the image's own (4), except on a CPU driver, which draws without multisampling. Lavapipe offers 1 or 4
// samples, and four cost the README's main job 1.6 times the wall time for edges
// that differ only along the string and the wands at 960x540; a live show there is also scaled up from a smaller
// image, so its edges are soft whatever the samples.
int samplesFor(const RenderOutputOptions& options, const std::string& deviceType);

// The drawn scale `run` renders at on `device` (as samplesFor): --render-scale when given; else 1, except on a CPU
// driver, whose frame costs its pixels: there it draws at kCpuDrawnScale of the size and the frames are scaled up
// (app/outputs/image_scale.h). docs/rendering.md shows the two side by side.
inline constexpr float kCpuDrawnScale = 0.75f;
float drawnScaleFor(const RenderOutputOptions& options, const std::string& deviceType);
std::string drawnScaleName(float scale);  // "0.75"

// `image` at `scale` of its size, at least 16 pixels a side.
RenderOptions drawnImage(RenderOptions image, float scale);

// Every how many simulation frames `run` draws a video frame on `device` (as samplesFor): the whole number nearest
// the simulation's frame rate over --video-fps, at least 1; without --video-fps every frame (the simulation's rate,
// 50 frames/s at h = 0.02 s), except on a CPU driver, where a frame's drawing costs about twice its simulation and the
// video takes kCpuVideoFps, the rate of broadcast video (docs/rendering.md "Video rate"). The video then plays at
// the simulation's rate over the stride: real time whatever the stride.
inline constexpr double kCpuVideoFps = 25.0;
int videoStrideFor(const RenderOutputOptions& options, const std::string& deviceType, double frameTime);

// The environment to reflect: the built-in outdoor sky, or an equirectangular PNG (sRGB, 2:1) converted to linear
// radiance. Throws naming the file when it cannot be read or is not 2:1.
EnvironmentImage loadEnvironment(const std::filesystem::path& path);

// Whether an `ffmpeg` executable is on PATH.
bool ffmpegAvailable();

// Raw RGB frames piped into ffmpeg, which encodes H.264 MP4: no temporary file per frame. ffmpeg is started
// without a shell (posix_spawnp with an argument vector), so any output path works, quotes and spaces
// included, and none can run a command; it runs in its own process group, so a Ctrl-C at the terminal reaches
// the run (which then closes the video properly) and not ffmpeg. ffmpeg writes PATH.partial (output_file.h),
// renamed over PATH when it has finished the file: a video that failed leaves the one that was there.
class VideoWriter {
 public:
  VideoWriter(const std::filesystem::path& path, int width, int height, double framesPerSecond);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;  // owns the pipe and the child process
  VideoWriter& operator=(const VideoWriter&) = delete;
  void write(const std::vector<uint8_t>& rgb);  // throws when ffmpeg stopped taking frames
  // Closes the pipe and waits for ffmpeg; throws if it failed.
  void close();

 private:
  std::filesystem::path path_;
  std::optional<PartialFile> file_;
  size_t frameBytes_;
  int pipe_ = -1;  // write end of ffmpeg's stdin
  int pid_ = -1;
};

// The renderer of a run and what it writes.
// The smallest image run --realtime draws while behind the wall clock, as a fraction of its drawn size: half its width
// and height, live's floor too (LiveOptions::minRenderScale).
inline constexpr double kRealtimeRunSmallestImage = 0.5;

class RunRenderer {
 public:
  RunRenderer(const RenderOutputOptions& options, const std::filesystem::path& outDir, Simulation& sim,
              const std::string& device);
  // Draws frame `index` of `sim`. The frame is drawn while the caller simulates the next two (Renderer::submit
  // keeps two frames in flight, a film on the Vulkan stepper's device copied there) and written (PNG, video) in
  // order, at the call after next or at finish().
  // `view`, when given, changes the frame before it is drawn (the mirror view).
  void frame(long index, Simulation& sim, const WandState& wands, const std::function<void(RenderFrame&)>& view = {});
  // Writes the frames still being drawn and closes the video; says what was written. An encoder that failed is
  // reported (stderr and videoError()), never thrown: the simulation's results are written whatever happened to
  // the video.
  void finish();
  [[nodiscard]] const std::string& videoError() const { return videoError_; }
  // Draws the next frames at `fraction` (0-1] of the drawn size: run --realtime lowers it while the machine is behind
  // the wall clock (RealTimePacer::renderScale, as live's dynamic resolution). The frames in flight are written
  // first; every frame is still scaled up to the image's size. finish() says how low it went.
  void setDynamicScale(double fraction);
  // When the device drew the frames written since the last call (Renderer::takeDrawnIntervals).
  [[nodiscard]] std::vector<Renderer::BusyInterval> takeDrawnIntervals() { return renderer_->takeDrawnIntervals(); }

 private:
  RenderOutputOptions options_;
  RenderOptions drawn_;      // the size the renderer draws at (options_.image's scaled by the drawn scale)
  RenderOptions fullDrawn_;  // drawn_ at a dynamic scale of 1
  double dynamicScale_ = 1.0, lowestDynamicScale_ = 1.0;
  long framesBelowFull_ = 0;  // frames drawn at a dynamic scale below 1
  std::filesystem::path outDir_;
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<VideoWriter> video_;
  bool filmOnDevice_ = false;
  int videoStride_ = 1;   // a video frame every this many simulation frames (videoStrideFor)
  long videoFrames_ = 0;  // frames written to the video
  FilmFraming framing_;
  std::string videoError_;  // why the video stopped (empty while it is fine)
  struct Drawing {
    Renderer::Ticket ticket;
    long index;
    bool png, video;
  };
  std::deque<Drawing> drawing_;  // frames submitted and not yet written, oldest first
  void writeDrawnFrame();        // the oldest of them
  void dropVideo(const std::string& why);
};

// The film in host memory as far as drawing it reads it: where the renderer draws the Vulkan stepper's film on the
// device (filmOnDevice), the framing and the hole rims need only where the particles are, and the state stays on the
// device but for its positions (Simulation::filmPositionsOnly); otherwise the whole film.
const Film& filmToDraw(Simulation& sim, bool filmOnDevice);

// The frame a renderer draws of a simulation: its film, droplets and wands, the film on the device when the
// stepper is the Vulkan stepper on `renderer`'s device. `deviceFilm` is storage for that case.
RenderFrame renderFrameOf(Simulation& sim, const WireFrame& wireFrame, const OrbitCamera& camera, bool filmOnDevice,
                          DeviceFilm& deviceFilm);

}  // namespace gb
