#include "render_output.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <sstream>

#include "png_image.h"
#include "vulkan_stepper.h"

namespace gb {

void addRenderOptions(CLI::App& command, RenderOutputOptions& o) {
  command.add_flag("--render", o.enabled, "render the film (interference colours, Vulkan) to PNG frames and video");
  command.add_option("--width", o.image.width, "rendered image width (pixels)")->check(CLI::Range(16, 16384));
  command.add_option("--height", o.image.height, "rendered image height (pixels)")->check(CLI::Range(16, 16384));
  command
      .add_option_function<std::string>(
          "--colouring", [&o](const std::string& name) { o.image.colouring = colouringFromName(name); },
          "film colouring: interference (default), thickness, airflow")
      ->check(CLI::IsMember({"interference", "thickness", "airflow"}));
  command.add_option("--render-every", o.pngEvery, "write a rendered PNG every N frames, 0 for none")
      ->check(CLI::Range(0, 1000000));
  command.add_option("--video", o.video,
                     "MP4 of every rendered frame, in the output folder (needs ffmpeg); '' for none");
  command.add_option("--environment", o.environment, "equirectangular PNG the film reflects (default: an outdoor sky)")
      ->check(CLI::ExistingFile);
  command
      .add_option_function<std::string>(
          "--camera", [&o](const std::string& mode) { o.followCamera = mode == "follow"; },
          "follow (default): keep the film framed at half the image height as it grows and drifts; fixed: the "
          "scene's camera as it is")
      ->check(CLI::IsMember({"follow", "fixed"}));
}

EnvironmentImage loadEnvironment(const std::filesystem::path& path) {
  if (path.empty()) return skyEnvironment();
  const RgbImage image = readPng(path);
  if (image.width != 2 * image.height)
    throw std::runtime_error("environment " + path.string() + " is " + std::to_string(image.width) + "x" +
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

VideoWriter::VideoWriter(const std::filesystem::path& path, int width, int height, double fps)
    : path_(path), frameBytes_(3ull * static_cast<size_t>(width) * static_cast<size_t>(height)) {
  // yuv420p needs even sizes: ffmpeg pads by one pixel where they are odd.
  const std::string command = "ffmpeg -loglevel error -y -f rawvideo -pix_fmt rgb24 -s " + std::to_string(width) + "x" +
                              std::to_string(height) + " -r " + std::to_string(fps) +
                              " -i - -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p -crf 18 '" +
                              path.string() + "'";
  std::signal(SIGPIPE, SIG_IGN);  // if ffmpeg dies, write() reports it instead of the run being killed
  pipe_ = popen(command.c_str(), "w");
  if (!pipe_) throw std::runtime_error("cannot start ffmpeg for " + path.string());
}

VideoWriter::~VideoWriter() {
  if (pipe_) pclose(pipe_);
}

void VideoWriter::write(const std::vector<uint8_t>& rgb) {
  if (!pipe_ || rgb.size() != frameBytes_) throw std::logic_error("VideoWriter::write: wrong frame size or closed");
  if (std::fwrite(rgb.data(), 1, rgb.size(), pipe_) != rgb.size())
    throw std::runtime_error("ffmpeg stopped taking frames for " + path_.string());
}

void VideoWriter::close() {
  if (!pipe_) return;
  const int status = pclose(pipe_);
  pipe_ = nullptr;
  if (status != 0) throw std::runtime_error("ffmpeg failed writing " + path_.string());
}

RenderFrame renderFrameOf(Simulation& sim, const WandState&, const WireFrame& wireFrame, const OrbitCamera& camera,
                          bool readInPlace, DeviceFilm& deviceFilm) {
  RenderFrame f;
  f.film = &sim.film();
  f.aerosol = &sim.aerosol();
  f.aerosolLifetime = sim.params().aerosolLifetime;
  f.wireFrame = &wireFrame;
  f.camera = camera;
  if (readInPlace) {
    deviceFilm = dynamic_cast<VulkanStepper&>(sim.stepper()).deviceFilm();
    f.deviceFilm = &deviceFilm;
  }
  return f;
}

RunRenderer::RunRenderer(const RenderOutputOptions& options, const std::filesystem::path& outDir, Simulation& sim,
                         const std::string& device)
    : options_(options), outDir_(outDir) {
  std::shared_ptr<const VulkanContext> context;
  if (auto* vulkan = dynamic_cast<VulkanStepper*>(&sim.stepper())) {
    context = vulkan->sharedContext();
    readInPlace_ = true;
  } else {
    try {
      context = std::make_shared<const VulkanContext>(device);
    } catch (const VulkanUnavailable& e) {
      throw std::runtime_error(std::string("--render needs a Vulkan device (lavapipe will do: mesa-vulkan-drivers): ") +
                               e.what());
    }
  }
  renderer_ = std::make_unique<Renderer>(context, options.image, loadEnvironment(options.environment));
  std::printf("render: %dx%d %s on %s, film read %s\n", options.image.width, options.image.height,
              colouringName(options.image.colouring), context->info().name.c_str(),
              readInPlace_ ? "in place from the Vulkan stepper's buffers" : "from the CPU state, uploaded each frame");
  if (!options.video.empty()) {
    if (ffmpegAvailable())
      video_ = std::make_unique<VideoWriter>(outDir / options.video, options.image.width, options.image.height,
                                             1.0 / sim.params().frameTime);
    else {
      options_.pngEvery = std::max(options_.pngEvery, 1);
      std::printf("render: ffmpeg is not installed, so no video; the frames are written as PNG instead\n");
    }
  }
}

void RunRenderer::frame(long index, Simulation& sim, const WandState& wands) {
  const bool png = options_.pngEvery > 0 && index % options_.pngEvery == 0;
  // The framing eases every frame, drawn or not, so that it moves at the same pace whatever is written.
  const OrbitCamera camera = options_.followCamera
                                 ? framing_.update(options_.camera, sim.film().state, sim.params().frameTime)
                                 : options_.camera;
  if (!png && !video_) return;
  const Vec3 gravity(sim.params().gravityX, sim.params().gravityY, sim.params().gravityZ);
  const WireFrame wire = makeWireFrame(sim.film().tool, wands, sim.film().stringLength, gravity);
  DeviceFilm deviceFilm;
  renderer_->render(renderFrameOf(sim, wands, wire, camera, readInPlace_, deviceFilm));
  const std::vector<uint8_t> rgb = renderer_->readPixels();
  if (png) {
    char name[40];
    std::snprintf(name, sizeof name, "render_%05ld.png", index);
    writePng(outDir_ / name, options_.image.width, options_.image.height, rgb);
  }
  if (video_) video_->write(rgb);
  ++written_;
}

void RunRenderer::finish() {
  if (video_) {
    video_->close();
    std::printf("render: %ld frames, video %s\n", written_, (outDir_ / options_.video).string().c_str());
  }
}

}  // namespace gb
