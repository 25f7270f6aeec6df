#include "app/outputs/render_output.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <utility>

#include "app/commands/cli_checks.h"
#include "app/outputs/child_process.h"
#include "app/outputs/image_scale.h"
#include "capture/output_file.h"
#include "capture/png_image.h"
#include "capture/untrusted.h"
#include "host/vulkan_stepper.h"

namespace gb {

namespace {

// --render, --render-every, --video and --video-fps on a command that writes no rendered files: refused by name, not
// shown.
void refuseRenderedFiles(CLI::App& command) {
  for (const char* name : {"--render", "--render-every", "--video", "--video-fps"})
    command
        .add_option_function<std::string>(
            name,
            [name](const std::string&) {
              throw CLI::ValidationError(name, std::string("live draws the show in its window and writes no files: ") +
                                                   "giantbubble run --render writes rendered frames and a video; "
                                                   "--stream sends the show's picture out");
            },
            "")
        ->expected(0, 1)
        ->group("");
}

}  // namespace

void addRenderOptions(CLI::App& command, RenderOutputOptions& o, RenderedFiles files) {
  if (files == RenderedFiles::Written) {
    command.add_flag("--render,!--no-render", o.enabled,
                     "render the film (interference colours, Vulkan) to PNG frames and video; --no-render: not even "
                     "a scene's own video (the default scene renders one)");
    command.add_option("--render-every", o.pngEvery, "write a rendered PNG every N frames, 0 for none")
        ->transform(WholeNumber(0, 1000000));
    command.add_option("--video", o.video, "MP4 of the run, in the output folder (needs ffmpeg); '' for none");
    command
        .add_option("--video-fps", o.videoFps,
                    "the video's frames per second, a frame every (simulation's rate / this) frames; default the "
                    "simulation's rate, " +
                        std::to_string(static_cast<int>(kCpuVideoFps)) + " on a CPU driver (lavapipe)")
        ->check(FiniteRange(1.0, 1000.0));
  } else {
    refuseRenderedFiles(command);
  }
  command.add_option("--width", o.image.width, "rendered image width (pixels)")->transform(WholeNumber(16, 16384));
  command.add_option("--height", o.image.height, "rendered image height (pixels)")->transform(WholeNumber(16, 16384));
  command
      .add_option_function<std::string>(
          "--colouring", [&o](const std::string& name) { o.image.colouring = colouringFromName(name); },
          "film colouring: interference (default), thickness, airflow")
      ->check(CLI::IsMember({"interference", "thickness", "airflow"}));
  command.add_option("--environment", o.environment, "equirectangular PNG the film reflects (default: an outdoor sky)")
      ->check(CLI::ExistingFile);
  command
      .add_option_function<std::string>(
          "--camera", [&o](const std::string& mode) { o.followCamera = mode == "follow"; },
          "follow (default): keep the film framed at half the image height as it grows and drifts; fixed: the "
          "scene's camera as it is")
      ->check(CLI::IsMember({"follow", "fixed"}));
  command
      .add_option_function<std::string>(
          "--view", [&o](const std::string& view) { o.mirror = view == "mirror"; },
          "stage (default): the virtual stage; mirror: the scene from the depth camera, mirrored, with the "
          "performer drawn in by depth (a camera input: kinect or fakenect:DIR)")
      ->check(CLI::IsMember({"stage", "mirror"}));
  command.add_flag("--mirror-room", o.mirrorRoom,
                   "in the mirror view, show the room the camera sees behind the performer instead of the virtual "
                   "stage");
  command
      .add_option("--samples", o.samples,
                  "multisample anti-aliasing, samples per pixel (1: none); default 4, 1 on a CPU driver (lavapipe)")
      ->transform(WholeNumber(1, 8))
      ->check(CLI::IsMember({1, 2, 4, 8}));
  if (files == RenderedFiles::Written)
    command
        .add_option("--render-scale", o.drawnScale,
                    "draw at this fraction of --width and --height and scale the frames up to it (0.25 to 1); "
                    "default 1, " +
                        drawnScaleName(kCpuDrawnScale) + " on a CPU driver (lavapipe)")
        ->check(FiniteRange(kSmallestDrawnScale, 1.0));
}

int samplesFor(const RenderOutputOptions& options, const std::string& deviceType) {
  if (options.samples > 0) return options.samples;
  return deviceType == "CPU" ? 1 : options.image.samples;
}

float drawnScaleFor(const RenderOutputOptions& options, const std::string& deviceType) {
  if (options.drawnScale > 0) return options.drawnScale;
  return deviceType == "CPU" ? kCpuDrawnScale : 1.0f;
}

int videoStrideFor(const RenderOutputOptions& options, const std::string& deviceType, double frameTime) {
  const double fps = options.videoFps > 0 ? options.videoFps : deviceType == "CPU" ? kCpuVideoFps : 0.0;
  if (fps <= 0) return 1;
  return static_cast<int>(std::clamp(std::lround(1.0 / (frameTime * fps)), 1L, 1000000L));
}

std::string drawnScaleName(float scale) {
  char text[16];
  std::snprintf(text, sizeof text, "%g", static_cast<double>(scale));
  return text;
}

RenderOptions drawnImage(RenderOptions image, float scale) {
  image.width = std::max(16, static_cast<int>(std::lround(scale * static_cast<float>(image.width))));
  image.height = std::max(16, static_cast<int>(std::lround(scale * static_cast<float>(image.height))));
  return image;
}

EnvironmentImage loadEnvironment(const std::filesystem::path& path) {
  if (path.empty()) return skyEnvironment();
  const RgbImage image = readPng(path);
  if (image.width != 2 * image.height)
    throw std::runtime_error("environment " + printablePath(path) + " is " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + "; an equirectangular image is twice as wide as high");
  EnvironmentImage env;
  env.width = image.width;
  env.height = image.height;
  env.rgb.resize(image.rgb.size());
  for (size_t i = 0; i < image.rgb.size(); ++i) {
    const float c = static_cast<float>(image.rgb[i]) / 255.0f;  // sRGB transfer curve to linear
    env.rgb[i] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
  }
  return env;
}

bool ffmpegAvailable() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && access((std::filesystem::path(dir) / "ffmpeg").c_str(), X_OK) == 0) return true;
  return false;
}

namespace {

// ffmpeg's arguments: raw RGB frames on stdin, H.264 MP4 out. The output is named "file:/absolute/path" so that
// no path is read as an option (a leading '-') or a protocol (a ':' in the name).
std::vector<std::string> ffmpegArguments(const std::filesystem::path& path, int width, int height, double fps) {
  return {"ffmpeg", "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
          std::to_string(width) + "x" + std::to_string(height), "-r", std::to_string(fps), "-i", "pipe:0",
          // yuv420p needs even sizes: ffmpeg pads by one pixel where they are odd.
          "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "18",
          // veryfast: the encoder shares the cores with the simulation and the renderer; at the default preset
          // it took 8% of the README's main job.
          "-preset", "veryfast",
          // MP4 whatever the name ends in: the file is NAME.mp4.partial until it is complete.
          "-f", "mp4", "file:" + std::filesystem::absolute(path).string()};
}

}  // namespace

VideoWriter::VideoWriter(const std::filesystem::path& path, int width, int height, double fps)
    : path_(path),
      file_(std::in_place, path),
      frameBytes_(3ull * static_cast<size_t>(width) * static_cast<size_t>(height)) {
  std::signal(SIGPIPE, SIG_IGN);  // if ffmpeg dies, write() reports it instead of the run being killed
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error("cannot make a pipe to ffmpeg: " + std::string(std::strerror(errno)));
  try {
    pid_ = spawnWithStdin(ffmpegArguments(file_->partialPath(), width, height, fps), fds[0]);
  } catch (const std::runtime_error& e) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string(e.what()) + " for " + printablePath(path));
  }
  ::close(fds[0]);
  pipe_ = fds[1];
}

VideoWriter::~VideoWriter() {
  try {
    close();
  } catch (const std::exception&) {  // a destructor cannot report; finish() already did where it mattered
  }
}

void VideoWriter::write(const std::vector<uint8_t>& rgb) {
  if (pipe_ < 0 || rgb.size() != frameBytes_) throw std::logic_error("VideoWriter::write: wrong frame size or closed");
  if (!writeAll(pipe_, std::string_view(reinterpret_cast<const char*>(rgb.data()), rgb.size())))
    throw std::runtime_error("ffmpeg stopped taking frames for " + printablePath(path_) + " (" + std::strerror(errno) +
                             ")");
}

void VideoWriter::close() {
  if (pipe_ >= 0) ::close(std::exchange(pipe_, -1));  // end of input: ffmpeg finishes the file
  if (pid_ < 0) return;
  int status = 0;
  while (waitpid(std::exchange(pid_, -1), &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    file_->commit();
    return;
  }
  file_.reset();  // the .partial goes; a video that was there stays
  throw std::runtime_error("ffmpeg failed writing " + printablePath(path_) +
                           (WIFEXITED(status) ? " (exit status " + std::to_string(WEXITSTATUS(status)) + ")"
                                              : " (killed by signal " + std::to_string(WTERMSIG(status)) + ")"));
}

const Film& filmToDraw(Simulation& sim, bool filmOnDevice) {
  return filmOnDevice ? sim.filmPositionsOnly() : sim.film();
}

RenderFrame renderFrameOf(Simulation& sim, const WireFrame& wireFrame, const OrbitCamera& camera, bool filmOnDevice,
                          DeviceFilm& deviceFilm) {
  RenderFrame f;
  f.film = &filmToDraw(sim, filmOnDevice);
  f.aerosol = &sim.aerosol();
  f.aerosolLifetime = sim.params().aerosolLifetime;
  f.blackFilmThickness = sim.params().blackFilmThickness;
  f.wireFrame = &wireFrame;
  f.camera = camera;
  if (filmOnDevice) {
    deviceFilm = dynamic_cast<VulkanStepper&>(sim.stepper()).deviceFilm();
    f.deviceFilm = &deviceFilm;
  }
  return f;
}

RunRenderer::RunRenderer(const RenderOutputOptions& options, const std::filesystem::path& outDir, Simulation& sim,
                         const std::string& device)
    : options_(options), outDir_(outDir) {
  FilmFraming::Options framing;
  framing.aspect = static_cast<float>(options.image.width) / static_cast<float>(options.image.height);
  framing_ = FilmFraming(framing);
  std::shared_ptr<const VulkanContext> context;
  if (auto* vulkan = dynamic_cast<VulkanStepper*>(&sim.stepper())) {
    context = vulkan->sharedContext();
    filmOnDevice_ = true;
  } else {
    try {
      context = std::make_shared<const VulkanContext>(device);
    } catch (const VulkanUnavailable& e) {
      throw std::runtime_error(std::string("--render needs a Vulkan device (lavapipe will do: mesa-vulkan-drivers): ") +
                               e.what());
    }
  }
  const float scale = drawnScaleFor(options, context->info().type);
  RenderOptions image = drawnImage(options.image, scale);
  image.samples = samplesFor(options, context->info().type);
  drawn_ = fullDrawn_ = image;
  renderer_ = std::make_unique<Renderer>(context, image, loadEnvironment(options.environment));
  std::printf("render: %dx%d %s, %d sample%s per pixel, on %s, film read %s\n", options.image.width,
              options.image.height, colouringName(image.colouring), image.samples, image.samples == 1 ? "" : "s",
              context->info().name.c_str(),
              filmOnDevice_ ? "from the Vulkan stepper's buffers, copied on the device"
                            : "from the CPU state, uploaded each frame");
  if (image.width != options.image.width || image.height != options.image.height)
    std::printf("render: drawn at %dx%d (scale %s, --render-scale) and scaled up to %dx%d\n", image.width, image.height,
                drawnScaleName(scale).c_str(), options.image.width, options.image.height);
  if (!options.video.empty()) {
    if (ffmpegAvailable()) {
      const std::filesystem::path video = outDir / options.video;
      std::filesystem::create_directories(video.parent_path());  // --video sub/show.mp4 makes sub, as --out does
      videoStride_ = videoStrideFor(options, context->info().type, sim.params().frameTime);
      const double fps = 1.0 / (static_cast<double>(sim.params().frameTime) * videoStride_);
      video_ = std::make_unique<VideoWriter>(video, options.image.width, options.image.height, fps);
      std::printf("render: video at %g frames/s (%s, --video-fps)\n", fps,
                  videoStride_ == 1 ? "every frame" : ("every " + std::to_string(videoStride_) + " frames").c_str());
    } else {
      options_.pngEvery = std::max(options_.pngEvery, 1);
      std::printf("render: ffmpeg is not installed, so no video; the frames are written as PNG instead\n");
    }
  }
}

void RunRenderer::frame(long index, Simulation& sim, const WandState& wands,
                        const std::function<void(RenderFrame&)>& view) {
  const bool png = options_.pngEvery > 0 && index % options_.pngEvery == 0;
  const bool video = video_ && index % videoStride_ == 0;
  // The framing eases every frame, drawn or not, so that it moves at the same pace whatever is written.
  const OrbitCamera camera =
      options_.followCamera
          ? framing_.update(options_.camera, filmToDraw(sim, filmOnDevice_).state, sim.params().frameTime)
          : options_.camera;
  if (!png && !video) return;
  // The renderer keeps two frames: the older is written before a third is submitted, and not on a frame that draws
  // nothing, so that it has every simulated frame until then to be drawn.
  while (drawing_.size() >= 2) writeDrawnFrame();
  const WireFrame wire = sim.wireFrame(wands);
  DeviceFilm deviceFilm;
  RenderFrame drawn = renderFrameOf(sim, wire, camera, filmOnDevice_, deviceFilm);
  if (view) view(drawn);
  const Renderer::Ticket ticket = renderer_->submit(drawn);
  drawing_.push_back({ticket, index, png, video});
  if (dynamicScale_ < 1.0) ++framesBelowFull_;
}

void RunRenderer::setDynamicScale(double fraction) {
  dynamicScale_ = std::clamp(fraction, 0.0, 1.0);
  lowestDynamicScale_ = std::min(lowestDynamicScale_, dynamicScale_);
  const RenderOptions next = drawnImage(fullDrawn_, static_cast<float>(dynamicScale_));
  if (next.width == drawn_.width && next.height == drawn_.height) return;
  while (!drawing_.empty()) writeDrawnFrame();  // each is scaled up from the size it was drawn at
  renderer_->resize(next.width, next.height);
  drawn_ = next;
}

void RunRenderer::writeDrawnFrame() {
  if (drawing_.empty()) return;
  const Drawing drawn = drawing_.front();
  drawing_.pop_front();
  const long index = drawn.index;
  const std::vector<uint8_t> rgb = scaleRgb(renderer_->readPixels(drawn.ticket), drawn_.width, drawn_.height,
                                            options_.image.width, options_.image.height);
  if (drawn.png) {
    char name[40];
    std::snprintf(name, sizeof name, "render_%05ld.png", index);
    writePng(outDir_ / name, options_.image.width, options_.image.height, rgb);
  }
  if (video_ && drawn.video) {
    try {
      video_->write(rgb);
      ++videoFrames_;
    } catch (const std::exception& e) {
      dropVideo(e.what());
    }
  }
}

void RunRenderer::dropVideo(const std::string& why) {
  videoError_ = why;
  try {
    video_->close();  // reaps ffmpeg; its own message is already on stderr
  } catch (const std::exception& e) {
    videoError_ += std::string("; ") + e.what();
  }
  video_.reset();
  std::fprintf(stderr, "warning: video: %s; the run goes on without it and writes its other outputs\n", why.c_str());
}

void RunRenderer::finish() {
  try {
    while (!drawing_.empty()) writeDrawnFrame();
  } catch (const std::exception& e) {  // the device was lost drawing them: the run's other outputs still matter
    std::fprintf(stderr, "error: render: the last frames: %s\n", e.what());
  }
  if (framesBelowFull_ > 0)
    std::printf("render: behind the wall clock, %ld frames drawn smaller, down to %.0f%% of %dx%d\n", framesBelowFull_,
                100.0 * lowestDynamicScale_, fullDrawn_.width, fullDrawn_.height);
  if (!video_) return;
  try {
    video_->close();
    video_.reset();
    std::printf("render: %ld frames, video %s\n", videoFrames_, printablePath(outDir_ / options_.video).c_str());
  } catch (const std::exception& e) {
    video_.reset();
    videoError_ = e.what();
    std::fprintf(stderr, "error: video: %s; the simulation's other outputs are written\n", e.what());
  }
}

}  // namespace gb
