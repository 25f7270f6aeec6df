// The renderer on lavapipe: a known scene against a stored reference image, the Vulkan stepper's buffers read in
// place against the same film uploaded from the host, and the diagnostic colourings. The validation layer is on
// (tests/vulkan_test_device.h) and must report no error.
//
// The reference image is tests/data/render_reference.png. Regenerate it only deliberately, after a change that
// is meant to change the picture, and look at it before committing:
//   GIANTBUBBLE_REGENERATE_REFERENCE=1 ./build/tests/gb_tests --gtest_filter=Renderer.KnownSceneMatchesReference
#include "host/renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "app/outputs/render_output.h"
#include "app/outputs/step_render_overlap.h"
#include "capture/png_image.h"
#include "capture/scripted_gestures.h"
#include "host/film_swirls.h"
#include "host/thin_film.h"
#include "host/vulkan_stepper.h"
#include "kernels/render/thin_film_lut.h"
#include "scene/scene_file.h"
#include "simulation/simulation.h"
#include "tests/render_scene_films.h"
#include "tests/test_films.h"
#include "tests/vulkan_test_device.h"

namespace gb {
namespace {

constexpr int kWidth = 240, kHeight = 160;

RenderOptions smallImage(Colouring colouring = Colouring::Interference) {
  RenderOptions o;
  o.width = kWidth;
  o.height = kHeight;
  o.colouring = colouring;
  o.thicknessVariation = 0.0f;  // the films' thickness as the tests set it (the swirls have tests of their own)
  return o;
}

struct PixelError {
  double mean = 0;           // mean absolute difference per channel (8-bit levels)
  int max = 0;               // largest difference of any channel
  double fractionOver8 = 0;  // fraction of pixels with a channel more than 8 levels off
};

PixelError compare(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  PixelError e;
  size_t over = 0;
  for (size_t p = 0; p < a.size() / 3; ++p) {
    int worst = 0;
    for (size_t c = 0; c < 3; ++c) {
      const int d = std::abs(int(a[3 * p + c]) - int(b[3 * p + c]));
      e.mean += d;
      worst = std::max(worst, d);
    }
    e.max = std::max(e.max, worst);
    over += worst > 8 ? 1 : 0;
  }
  e.mean /= static_cast<double>(a.size());
  e.fractionOver8 = static_cast<double>(over) / static_cast<double>(a.size() / 3);
  return e;
}

// Largest channel difference between the two pictures each averaged over 3x3 pixels: an edge or a sub-pixel
// droplet that another rasteriser draws a pixel over, or spreads over two pixels instead of one, keeps its light
// in the average and differs little, while a wrong colour over a patch of 3x3 pixels or more differs in full.
double largestDifferenceOf3x3Averages(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int width) {
  const int height = static_cast<int>(a.size() / 3) / width;
  double largest = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        int sum = 0, count = 0;
        for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny)
          for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx, ++count)
            sum += int(a[3 * (ny * width + nx) + c]) - int(b[3 * (ny * width + nx) + c]);
        largest = std::max(largest, std::abs(static_cast<double>(sum)) / count);
      }
  return largest;
}

TEST(Renderer, KnownSceneMatchesReference) {
  GB_REQUIRE_VULKAN(device);
  const test::KnownScene scene = test::makeKnownScene();
  Renderer renderer(device, smallImage(), studioEnvironment(256));
  renderer.render(test::frameOf(scene));
  const std::vector<uint8_t> pixels = renderer.readPixels();
  writePng("render_actual.png", kWidth, kHeight, pixels);  // beside the test binary, to look at on failure
  const std::filesystem::path reference = std::filesystem::path(GB_TEST_DATA_DIR) / "render_reference.png";
  if (const char* regenerate = std::getenv("GIANTBUBBLE_REGENERATE_REFERENCE");
      regenerate && std::string(regenerate) == "1") {
    writePng(reference, kWidth, kHeight, pixels);
    GTEST_SKIP() << "*** reference image REGENERATED at " << reference << ": look at it before committing ***";
  }
  const RgbImage expected = readPng(reference);
  ASSERT_EQ(expected.width, kWidth);
  ASSERT_EQ(expected.height, kHeight);
  const PixelError e = compare(pixels, expected.rgb);
  const double averagedMax = largestDifferenceOf3x3Averages(pixels, expected.rgb, kWidth);
  std::printf(
      "against the reference: mean %.3f levels, max %d (%.1f over 3x3 averages), %.4f%% of pixels over 8 "
      "levels\n",
      e.mean, e.max, averagedMax, 100 * e.fractionOver8);
  // Tolerances: the same driver gives the same picture bit for bit; another LLVM or Mesa version, or a real GPU,
  // may round the half-float targets and the transcendental functions differently (a level or two) and move a
  // few triangle-edge or droplet pixels. A mean over 1 level, or more than 1% of pixels off by over 8 levels, is a
  // changed picture: an NVIDIA H100 moves 0.50% of the pixels by over 8 levels (mean 0.32 levels), lavapipe 0.11%.
  // The largest difference is bounded at 64 levels over 3x3 averages, so that moved edges and droplets pass (on
  // lavapipe and on the H100 alike they differ by up to 185 levels pixel for pixel, 48.6 averaged) while a wrong
  // colour over any patch of the film does not hide among them.
  EXPECT_LT(e.mean, 1.0);
  EXPECT_LT(e.fractionOver8, 0.01);
  EXPECT_LE(averagedMax, 64.0);
  EXPECT_EQ(device->validationErrors(), 0u);
}

// The live window's dynamic resolution: a renderer drawn smaller and back draws the same picture as before (the
// same driver gives the same pixels bit for bit; the swirls are off in the known scene), and the smaller one is the
// size asked for.
TEST(Renderer, ResizedAndBackDrawsTheSamePicture) {
  GB_REQUIRE_VULKAN(device);
  const test::KnownScene scene = test::makeKnownScene();
  Renderer renderer(device, smallImage(), studioEnvironment(256));
  renderer.render(test::frameOf(scene));
  const std::vector<uint8_t> before = renderer.readPixels();
  renderer.resize(kWidth / 2, kHeight / 2);
  renderer.render(test::frameOf(scene));
  EXPECT_EQ(renderer.readPixels().size(), static_cast<size_t>(3 * (kWidth / 2) * (kHeight / 2)));
  EXPECT_EQ(renderer.options().width, kWidth / 2);
  renderer.resize(kWidth, kHeight);
  renderer.render(test::frameOf(scene));
  EXPECT_EQ(renderer.readPixels(), before);
  EXPECT_THROW(renderer.resize(8, 8), std::invalid_argument);
  EXPECT_EQ(device->validationErrors(), 0u);
}

// `giantbubble run` writes frame N while N + 1 is drawn and N + 2 simulated (Renderer::submit, two frames in
// flight): what a frame points to is copied before submit returns, so changing the film afterwards does not change
// its picture; each frame is read back as its film was, in any order; a frame three submits old is refused, not
// misread.
TEST(Renderer, SubmittedFramesAreReadBackAsTheirFilmWasTwoInFlight) {
  GB_REQUIRE_VULKAN(device);
  test::KnownScene scene = test::makeKnownScene();
  Renderer renderer(device, smallImage(), studioEnvironment(256));
  renderer.render(test::frameOf(scene));
  const std::vector<uint8_t> before = renderer.readPixels();
  const Renderer::Ticket first = renderer.submit(test::frameOf(scene));
  State& s = scene.film.state;
  for (size_t i = 0; i < s.size(); ++i) s.position.set(i, s.position.get(i) + Vec3(0.3f, 0.2f, 0.0f));
  const Renderer::Ticket second = renderer.submit(test::frameOf(scene));
  // The newer first: reading one frame does not disturb the other's pixels.
  const std::vector<uint8_t> moved = renderer.readPixels(second);
  EXPECT_GT(compare(moved, before).mean, 1.0);  // the moved film is seen: the known scene's film covers the middle
  EXPECT_EQ(compare(renderer.readPixels(first), before).max, 0);  // same floats, same shaders: to the bit
  renderer.submit(test::frameOf(scene));                          // reuses the first frame's slot
  EXPECT_THROW((void)renderer.readPixels(first), std::logic_error);
  EXPECT_EQ(compare(renderer.readPixels(second), moved).max, 0);
  EXPECT_EQ(compare(renderer.readPixels(), moved).max, 0);  // the last submitted: the same film as `second`
  EXPECT_EQ(device->validationErrors(), 0u);
}

// `run` tells how much of its step the render overlapped from the device's own timestamps read on the host's steady
// clock: each frame waited for is one interval, inside the wall time from its submit to its wait, oldest first,
// taken once. Lavapipe has calibrated timestamps (so CI checks them); a device without is named and not timed.
TEST(Renderer, EachFrameDrawnIsTimedOnTheHostClock) {
  GB_REQUIRE_VULKAN(device);
  const test::KnownScene scene = test::makeKnownScene();
  Renderer renderer(device, smallImage(), studioEnvironment(256));
  const auto now = [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  };
  const double before = now();
  renderer.submit(test::frameOf(scene));
  renderer.submit(test::frameOf(scene));
  renderer.wait();
  const double after = now();
  const std::vector<Renderer::BusyInterval> drawn = renderer.takeDrawnIntervals();
  if (!device->timestampsOnHostClock()) {
    EXPECT_TRUE(drawn.empty());
    GTEST_SKIP() << "*** " << device->info().name << " has no timestamps on the host clock: frames not timed ***";
  }
  ASSERT_EQ(drawn.size(), 2u);
  // Tolerance 1 ms: the calibration's own deviation is nanoseconds on lavapipe and microseconds on a GPU.
  for (const Renderer::BusyInterval& d : drawn) {
    EXPECT_GE(d.start, before - 1e-3);
    EXPECT_LE(d.end, after + 1e-3);
    EXPECT_LT(d.start, d.end);
  }
  EXPECT_LE(drawn[0].end, drawn[1].start + 1e-3);  // one queue: the second frame is drawn after the first
  EXPECT_TRUE(renderer.takeDrawnIntervals().empty());
  EXPECT_EQ(device->validationErrors(), 0u);
}

// The Vulkan stepper's film is copied on the device into the frame's own buffers: the same pixels as the film
// uploaded from the host. `run` and `live` step again while such a frame is drawn, and the stepper then rewrites the
// buffers the frame was submitted from: the frame is drawn from its copy, taken before submit returned.
TEST(Renderer, DrawsTheVulkanSteppersFilmAsItWasWhenSubmitted) {
  GB_REQUIRE_VULKAN(device);
  test::KnownScene scene = test::makeKnownScene();
  Params params;
  VulkanStepper stepper(device);
  stepper.load(params, scene.film);
  const DeviceFilm onDevice = stepper.deviceFilm();
  Renderer renderer(device, smallImage(), studioEnvironment(256));
  RenderFrame frame = test::frameOf(scene);
  renderer.render(frame);
  const std::vector<uint8_t> uploaded = renderer.readPixels();
  frame.deviceFilm = &onDevice;
  const Renderer::Ticket submitted = renderer.submit(frame);
  State& s = scene.film.state;  // the stepper's buffers rewritten while the frame may still be drawn
  for (size_t i = 0; i < s.size(); ++i) s.position.set(i, s.position.get(i) + Vec3(0.3f, 0.2f, 0.0f));
  stepper.load(params, scene.film);
  const DeviceFilm moved = stepper.deviceFilm();
  frame.deviceFilm = &moved;
  const Renderer::Ticket next = renderer.submit(frame);
  // Same floats through the same shaders: identical to the bit.
  EXPECT_EQ(compare(uploaded, renderer.readPixels(submitted)).max, 0);
  EXPECT_GT(compare(uploaded, renderer.readPixels(next)).mean, 1.0);  // and the moved film is seen after
  // And the film is there at all: the picture differs from one without the film.
  test::KnownScene empty = test::makeKnownScene();
  empty.film.topology.triangles.clear();
  renderer.render(test::frameOf(empty));
  EXPECT_GT(compare(uploaded, renderer.readPixels()).mean, 1.0);
  EXPECT_EQ(device->validationErrors(), 0u);
}

// `run` and `live` count the Vulkan stepper's step as its batch on the device (VulkanStepper::lastStepOnDevice): a
// step submitted behind a frame being drawn waits for it in the queue, and waiting is not stepping while drawing.
// The interval lies inside the host's call; on a CPU driver (lavapipe), whose one queue runs the submissions in turn,
// it starts after the frame submitted before it was drawn.
TEST(Renderer, AStepBehindAFrameIsTimedWhereTheDeviceRanIt) {
  GB_REQUIRE_VULKAN(device);
  if (!device->timestampsOnHostClock())
    GTEST_SKIP() << "*** " << device->info().name << " has no timestamps on the host clock: steps not timed ***";
  Params params;
  Simulation sim(params, generateSphere(params, Vec3(0, 1.5f, 0), 0.4f, 3), WandState{},
                 std::make_unique<VulkanStepper>(device));
  const auto& stepper = dynamic_cast<const VulkanStepper&>(sim.stepper());
  EXPECT_FALSE(stepper.lastStepOnDevice().has_value());
  RenderOptions large = smallImage();
  large.width = 960;  // a frame that takes the device a while
  large.height = 540;
  Renderer renderer(device, large, studioEnvironment(256));
  const test::KnownScene scene = test::makeKnownScene();
  renderer.submit(test::frameOf(scene));
  const double before = steadySeconds(std::chrono::steady_clock::now());
  sim.advanceFrame(WandState{});
  const double after = steadySeconds(std::chrono::steady_clock::now());
  renderer.wait();
  const std::optional<DeviceBusyInterval> step = stepper.lastStepOnDevice();
  const std::vector<Renderer::BusyInterval> drawn = renderer.takeDrawnIntervals();
  ASSERT_TRUE(step.has_value());
  ASSERT_EQ(drawn.size(), 1u);
  // Tolerance 1 ms: the calibration's own deviation is nanoseconds on lavapipe and microseconds on a GPU.
  EXPECT_GE(step->start, before - 1e-3);
  EXPECT_LE(step->end, after + 1e-3);
  EXPECT_LT(step->start, step->end);
  if (device->info().type == "CPU") {
    EXPECT_GE(step->start, drawn[0].end - 1e-3);
  }
  EXPECT_EQ(device->validationErrors(), 0u);
}

// Mean colour of a small window of the image around (x, y).
std::array<double, 3> meanColour(const std::vector<uint8_t>& rgb, int x, int y) {
  std::array<double, 3> sum{};
  int n = 0;
  for (int j = y - 2; j <= y + 2; ++j)
    for (int i = x - 2; i <= x + 2; ++i, ++n)
      for (size_t c = 0; c < 3; ++c) sum[c] += rgb[3 * (static_cast<size_t>(j) * kWidth + i) + c];
  for (double& s : sum) s /= n;
  return sum;
}

TEST(Renderer, ThicknessColouringIsBlueWhereThinAndRedWhereThick) {
  GB_REQUIRE_VULKAN(device);
  test::KnownScene scene = test::makeKnownScene();
  RenderOptions options = smallImage(Colouring::Thickness);
  options.thickColour = 1.2e-6f;  // the scene's thickest film shows red
  Renderer renderer(device, options, studioEnvironment(256));
  renderer.render(test::frameOf(scene));
  const std::vector<uint8_t> rgb = renderer.readPixels();
  writePng("render_thickness.png", kWidth, kHeight, rgb);
  // The bubble (radius 0.5 m seen from 2.6 m in a 0.75 rad field of view) spans rows 80 -+ 41: sample near
  // its top and bottom on the centre column, inside the outline.
  const auto top = meanColour(rgb, kWidth / 2, 48), bottom = meanColour(rgb, kWidth / 2, 112);
  EXPECT_GT(top[0], top[2] + 60) << "top: thick, red";
  EXPECT_GT(bottom[2], bottom[0] + 60) << "bottom: thin, blue";
  EXPECT_EQ(device->validationErrors(), 0u);
}

TEST(Renderer, OverlappingSheetsDoNotDependOnDrawingOrder) {
  // The bubble's two walls overlap everywhere inside its outline. Drawing its triangles in the reverse order
  // changes only the order of the float additions in the blender: at most 1 level anywhere (half-float sums
  // rounded differently), against the several levels a wrong order-dependent blend would show.
  GB_REQUIRE_VULKAN(device);
  test::KnownScene scene = test::makeKnownScene();
  Renderer renderer(device, smallImage(), studioEnvironment(256));
  renderer.render(test::frameOf(scene));
  const std::vector<uint8_t> forward = renderer.readPixels();
  std::vector<uint32_t>& tris = scene.film.topology.triangles;
  std::vector<uint32_t> reversed;
  for (size_t t = tris.size() / 3; t-- > 0;)
    reversed.insert(reversed.end(), {tris[3 * t], tris[3 * t + 1], tris[3 * t + 2]});
  tris = reversed;
  renderer.render(test::frameOf(scene));
  const PixelError e = compare(forward, renderer.readPixels());
  EXPECT_LE(e.max, 1);
  EXPECT_EQ(device->validationErrors(), 0u);
}

// sRGB encoding of a linear value in [0, 1], as the output image's format does it (IEC 61966-2-1).
double encodeSrgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

TEST(Renderer, FilmShowsItsInterferenceColourEndToEnd) {
  // A flat film of uniform thickness seen straight on, in an environment that is white (radiance 1) behind the
  // camera and black behind the film: it reflects R(e) of the white and transmits 1 - Y of the black, so the
  // film pixel in the middle is R per channel, then the resolve's shoulder (identity below 0.8) and the sRGB
  // curve. This checks the table's upload (half floats), its texture coordinates and the transparency resolve
  // against the CPU's numbers. Tolerance 3 levels of 255: half-float storage of the table and of the
  // transparency targets (11 significant bits).
  GB_REQUIRE_VULKAN(device);
  const Params params;
  const float thickness = 200e-9f;  // first-order magenta
  std::vector<Vec3> corners = {{-2.0f, -0.8f, 0.0f}, {2.0f, -0.8f, 0.0f}, {2.0f, 3.2f, 0.0f}, {-2.0f, 3.2f, 0.0f}};
  Film film = test::makeFilm(params, corners, {0, 1, 2, 0, 2, 3});
  for (size_t i = 0; i < film.state.size(); ++i) {
    film.state.thickness[i] = thickness;
    film.state.normal.set(i, Vec3::UnitZ());
  }
  EnvironmentImage lit;  // columns 16..47 look along -z (behind the film): black; the rest, +z: white
  lit.width = 64;
  lit.height = 32;
  lit.rgb.assign(64 * 32 * 3, 1.0f);
  for (int row = 0; row < 32; ++row)
    for (int col = 16; col < 48; ++col)
      for (int c = 0; c < 3; ++c) lit.rgb[3 * (static_cast<size_t>(row) * 64 + col) + c] = 0.0f;
  Renderer renderer(device, smallImage(), lit);
  RenderFrame frame;
  frame.film = &film;
  frame.camera.target = Vec3(0.0f, 1.2f, 0.0f);
  frame.camera.pitch = 0.0f;
  frame.camera.yaw = 0.0f;  // straight on
  renderer.render(frame);
  const std::vector<uint8_t> rgb = renderer.readPixels();
  writePng("render_flat_film.png", kWidth, kHeight, rgb);

  const auto r = sampleThinFilmLut(buildThinFilmLut(GB_FILM_INDEX), thickness, 1.0f);
  const auto centre = meanColour(rgb, kWidth / 2, kHeight / 2);
  std::printf("200 nm film, middle of the image: %.1f %.1f %.1f (8-bit sRGB)\n", centre[0], centre[1], centre[2]);
  for (size_t c = 0; c < 3; ++c) {
    const double radiance = r[c];
    const double shoulder = radiance / (1.0 + std::max(radiance - 0.8, 0.0));
    EXPECT_NEAR(centre[c], 255.0 * encodeSrgb(shoulder), 3.0) << "channel " << c;
  }
  // And it is magenta: green is the band the film cancels.
  EXPECT_LT(centre[1] + 20, centre[0]);
  EXPECT_LT(centre[1] + 20, centre[2]);
  EXPECT_EQ(device->validationErrors(), 0u);
}

// Largest difference of any channel between `image` (width x height) and `fine` (factor x the size), box-filtered
// down: how far a pixel is from the pixel an ideal anti-aliasing filter would give.
int worstAgainstSupersampled(const std::vector<uint8_t>& image, const std::vector<uint8_t>& fine, int width, int height,
                             int factor) {
  int worst = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i)
            sum += fine[3 * (static_cast<size_t>(y * factor + j) * width * factor + (x * factor + i)) + c];
        const int box = static_cast<int>(std::lround(sum / (factor * factor)));
        worst = std::max(worst, std::abs(box - image[3 * (static_cast<size_t>(y) * width + x) + c]));
      }
  return worst;
}

TEST(Renderer, StringWandsAndGroundEdgesAreAntiAliased) {
  // The edge-contrast statistic: every pixel against a 4x4 supersampled rendering of the same frame, box
  // filtered (the ideal a pixel of an anti-aliased edge approaches). A stepped edge pixel is off by up to the
  // full contrast of the edge (the white string on the dark ground: about 150 levels); 4x MSAA's coverage is
  // within a quarter of the 16-sample box's on any edge, so no pixel may be off by more than 64 levels. Shading is per
  // pixel in both, so only coverage differs. Without MSAA the same statistic must see the steps (more than 64), or it
  // proves nothing.
  GB_REQUIRE_VULKAN(device);
  test::KnownScene scene = test::makeKnownScene();
  scene.film.topology.triangles.clear();  // only the props: the string, the wands, the ground and its horizon
  scene.camera.yaw = 0.5f;
  scene.camera.pitch = 0.3f;  // the string and the ground's far edge both cross the picture at a slant
  RenderFrame frame = test::frameOf(scene);
  frame.aerosol = nullptr;
  const auto draw = [&](int factor, int samples) {
    RenderOptions o = smallImage();
    o.width = kWidth * factor;
    o.height = kHeight * factor;
    o.samples = samples;
    o.minTubePixels *= static_cast<float>(factor);  // the same width in the picture at every size
    Renderer renderer(device, o, skyEnvironment(256));
    renderer.render(frame);
    return renderer.readPixels();
  };
  const std::vector<uint8_t> fine = draw(4, 1), msaa = draw(1, 4), stepped = draw(1, 1);
  writePng("render_msaa.png", kWidth, kHeight, msaa);
  const int msaaWorst = worstAgainstSupersampled(msaa, fine, kWidth, kHeight, 4);
  const int steppedWorst = worstAgainstSupersampled(stepped, fine, kWidth, kHeight, 4);
  std::printf("worst pixel against 4x4 supersampling: %d levels with 4x MSAA, %d without\n", msaaWorst, steppedWorst);
  EXPECT_LE(msaaWorst, 64);
  EXPECT_GT(steppedWorst, 64);
  EXPECT_EQ(device->validationErrors(), 0u);
}

// The default sky with its colour taken out: whatever colour a film pixel has then comes from the film.
EnvironmentImage neutralSky() {
  EnvironmentImage env = skyEnvironment(256);
  for (size_t i = 0; i < env.rgb.size(); i += 3) {
    const float y = 0.2126f * env.rgb[i] + 0.7152f * env.rgb[i + 1] + 0.0722f * env.rgb[i + 2];
    env.rgb[i] = env.rgb[i + 1] = env.rgb[i + 2] = y;
  }
  return env;
}

// HSV saturation of an 8-bit pixel.
double saturation(const uint8_t* p) {
  const int hi = std::max({p[0], p[1], p[2]}), lo = std::min({p[0], p[1], p[2]});
  return hi > 0 ? static_cast<double>(hi - lo) / hi : 0.0;
}

// The default performance (scenes/default.toml) as the README's main job runs it, at its full 9,500 particles
// (coarser films of the same stroke burst before the wands close: 1,500 particles at 1.6 s, 5,000 at 1.9 s), with
// the run's follow camera (FilmFraming, eased every frame as `giantbubble run --render` does, at the test image's
// aspect). Simulated once for the tests that look at it (about 10 s on two cores): the film and camera mid-stroke
// (1.6 s: 0.5 s rest, then the bag drawn out, the wands starting to close) and at the film's peak area (the bag
// just closed into the free bubble).
struct DefaultPerformanceFrames {
  Film midStroke, atPeak;
  OrbitCamera midStrokeCamera, peakCamera;
  double peakArea = 0, peakTime = 0;
};

const DefaultPerformanceFrames& defaultPerformanceFrames() {
  static const DefaultPerformanceFrames frames = [] {
    DefaultPerformanceFrames r;
    const Scene scene = resolveScene("default");
    const Params& params = scene.run.params;
    const GestureOptions& stroke = scene.run.gestureOptions;
    Simulation sim(params, WandTool{}, gestureAt(Gesture::Giant, stroke, 0.0));
    FilmFraming::Options framingOptions;
    framingOptions.aspect = static_cast<float>(kWidth) / kHeight;
    FilmFraming framing(framingOptions);
    framing.update(OrbitCamera{}, sim.film().state, params.frameTime);
    for (int f = 1; f <= 125; ++f) {  // to 2.5 s: the free bubble has rounded up, the area is past its peak
      sim.advanceFrame(gestureAt(Gesture::Giant, stroke, static_cast<double>(f) * params.frameTime));
      const OrbitCamera camera = framing.update(OrbitCamera{}, sim.film().state, params.frameTime);
      if (f == 80) {
        r.midStroke = sim.film();
        r.midStrokeCamera = camera;
      }
      if (sim.stats().area > r.peakArea) {
        r.peakArea = sim.stats().area;
        r.peakTime = sim.stats().time;
        r.atPeak = sim.film();
        r.peakCamera = camera;
      }
    }
    return r;
  }();
  return frames;
}

// A frame drawn with the film and again without it (the props, ground and environment alone), to tell the film's
// pixels from the rest.
struct WithAndWithoutFilm {
  std::vector<uint8_t> with, without;
  // Largest change of any channel the film makes to pixel p (8-bit levels).
  [[nodiscard]] int change(size_t p) const {
    int largest = 0;
    for (size_t c = 0; c < 3; ++c)
      largest = std::max(largest, std::abs(int(with[3 * p + c]) - int(without[3 * p + c])));
    return largest;
  }
};

WithAndWithoutFilm drawWithAndWithoutFilm(Renderer& renderer, const Film& film, const OrbitCamera& camera) {
  RenderFrame frame;
  frame.film = &film;
  frame.camera = camera;
  WithAndWithoutFilm r;
  renderer.render(frame);
  r.with = renderer.readPixels();
  Film none = film;
  none.topology.triangles.clear();
  frame.film = &none;
  renderer.render(frame);
  r.without = renderer.readPixels();
  return r;
}

TEST(Renderer, DefaultCameraFramesTheGiantBubbleLarge) {
  // The film covers >= 15% of the image at peak from the default camera, at the frame of the
  // default performance's peak film area. Covered: a pixel the film changes by more than 8 levels when drawn in
  // the thickness colouring (mostly opaque sheets, alpha 0.75). The interference colouring cannot measure
  // coverage: a clear film over a background about as bright as what it reflects changes a pixel by a level or
  // two. Measured: 20.5% from the default camera looking up at 0.15 rad (20.0% from 0.3 rad down before it; a round
  // bubble whose outline spans 0.55 of this 3:2 image's height covers 16%; the level camera framing the bounding
  // sphere before those: 9.7%).
  GB_REQUIRE_VULKAN(device);
  const DefaultPerformanceFrames& frames = defaultPerformanceFrames();
  Renderer renderer(device, smallImage(Colouring::Thickness), neutralSky());
  const WithAndWithoutFilm drawn = drawWithAndWithoutFilm(renderer, frames.atPeak, frames.peakCamera);
  writePng("render_coverage.png", kWidth, kHeight, drawn.with);
  size_t covered = 0;
  for (size_t p = 0; p < drawn.with.size() / 3; ++p) covered += drawn.change(p) > 8 ? 1 : 0;
  const double coverage = static_cast<double>(covered) / (kWidth * kHeight);
  std::printf("peak area %.2f m^2 at %.2f s: the film covers %.1f%% of the image\n", frames.peakArea, frames.peakTime,
              100.0 * coverage);
  EXPECT_GE(coverage, 0.15);
  EXPECT_EQ(device->validationErrors(), 0u);
}

double srgbToLinear(uint8_t v) {
  const double c = v / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double linearLuminance(const uint8_t* p) {
  return 0.2126 * srgbToLinear(p[0]) + 0.7152 * srgbToLinear(p[1]) + 0.0722 * srgbToLinear(p[2]);
}

// Where a film pixel's colour comes from (printed, for whoever works on it next): the drawn thickness (with the
// swirls), the reflectance's spread over the colour channels and its luminance at the view angle, the luminance of
// what the film reflects (the environment in the mirror direction), all weighted by each particle's projected
// area (what the pixels see); and over the film's pixels the luminance behind the film and with it.
void printWhereTheColourComesFrom(const Film& film, const OrbitCamera& camera, const EnvironmentImage& env,
                                  const WithAndWithoutFilm& drawn) {
  const State& s = film.state;
  FilmSwirls swirls(RenderOptions{}.thicknessVariation);
  const std::vector<float>& factor = swirls.update(s);
  const ThinFilmLut lut = buildThinFilmLut(GB_FILM_INDEX);
  const Vec3 eye = camera.position();
  std::printf("camera: eye %.2f m above the ground, pitch %.3f rad, %.2f m from its target\n", eye.y(), camera.pitch,
              camera.distance);
  std::vector<std::pair<float, double>> thickness;  // drawn thickness, projected area
  double sum = 0, spread = 0, luminance = 0, reflected = 0, belowHorizon = 0, under1um = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s.alive[i]) continue;
    const Vec3 toEye = eye - s.position.get(i);
    const Vec3 v = toEye.normalized();
    Vec3 n = s.normal.get(i);
    if (n.dot(v) < 0) n = -n;
    const double w = s.voronoiArea[i] * n.dot(v) / toEye.squaredNorm();
    const float e = s.thickness[i] * factor[i];
    const auto r = sampleThinFilmLut(lut, e, n.dot(v));
    const Vec3 mirror = (2.0f * n.dot(v) * n - v).normalized();
    const int col =
        std::clamp(static_cast<int>((0.5f + std::atan2(mirror.x(), -mirror.z()) / (2.0f * std::numbers::pi_v<float>)) *
                                    static_cast<float>(env.width)),
                   0, env.width - 1);
    const int row = std::clamp(static_cast<int>(std::acos(std::clamp(mirror.y(), -1.0f, 1.0f)) /
                                                std::numbers::pi_v<float> * static_cast<float>(env.height)),
                               0, env.height - 1);
    const float* c = &env.rgb[3 * (static_cast<size_t>(row) * static_cast<size_t>(env.width) + col)];
    thickness.emplace_back(e, w);
    sum += w;
    spread += w * (std::max({r[0], r[1], r[2]}) - std::min({r[0], r[1], r[2]}));
    luminance += w * r[3];
    reflected += w * (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]);
    belowHorizon += mirror.y() < 0 ? w : 0;
    under1um += e < 1e-6f ? w : 0;
  }
  std::sort(thickness.begin(), thickness.end());
  const auto percentile = [&](double q) {
    double below = 0;
    for (const auto& [e, w] : thickness)
      if ((below += w) >= q * sum) return e;
    return thickness.back().first;
  };
  std::printf("drawn thickness: 10th percentile %.2f um, median %.2f um, 90th %.2f um, %.0f%% under 1 um\n",
              1e6 * percentile(0.1), 1e6 * percentile(0.5), 1e6 * percentile(0.9), 100 * under1um / sum);
  std::printf(
      "reflectance: spread (max - min channel) %.3f, luminance %.3f; reflected luminance %.3f (%.0f%% of it "
      "the ground)\n",
      spread / sum, luminance / sum, reflected / sum, 100 * belowHorizon / sum);
  double behind = 0, with = 0, pixels = 0;
  for (size_t p = 0; p < drawn.with.size() / 3; ++p) {
    if (drawn.change(p) <= 2) continue;
    behind += linearLuminance(&drawn.without[3 * p]);
    with += linearLuminance(&drawn.with[3 * p]);
    ++pixels;
  }
  std::printf("film pixels: luminance behind the film %.3f, with it %.3f\n", behind / pixels, with / pixels);
}

TEST(Renderer, DefaultPerformancesFilmIsColourfulMidStroke) {
  // Mean saturation of the film's pixels > 0.1 mid-stroke: the default performance mid-stroke (1.6 s),
  // drawn from the default camera framing it, in the default outdoor environment with its colour removed (every
  // texel, the sky, the wood behind the stage and the ground, replaced by its luminance) so that only interference
  // can colour a pixel. The film's pixels are those the film changes (by more than 2 levels in a channel) against the
  // same frame without it; saturation is HSV's (max - min) / max of the 8-bit pixel, averaged over them.
  //
  // What a film adds to a pixel is its reflectance R times what it reflects (S) over (1 - Y) times what is behind it
  // (B): its colour on the picture is the spread of R over the channels times S, divided by the pixel's brightness,
  // mostly B. The default camera stands low (pitch -0.15: its eye 0.8 m above the ground mid-stroke, looking up at
  // the film) and sees the film against the dark edge of the wood behind the stage, as giant bubbles are usually
  // photographed (docs/rendering.md, "Colour mid-stroke"). Measured (printed below): behind the film's pixels a
  // luminance of 0.046, with the film 0.095; the film reflects 0.398, 58% of it the ground; drawn thickness 0.45 /
  // 0.69 / 1.32 um (10th percentile, median, 90th); mean saturation 0.222 on 24% of the image. The bound is 0.1: the
  // margin is far beyond what another Mesa or LLVM version moves (a level or two on a few pixels, under 0.005 here),
  // and a change that puts sunlit ground or sky back behind the film (0.055 over asphalt with a camera 0.3 rad down)
  // or greys the film's reflection fails it.
  GB_REQUIRE_VULKAN(device);
  const DefaultPerformanceFrames& frames = defaultPerformanceFrames();
  RenderOptions o = smallImage();
  o.thicknessVariation = RenderOptions{}.thicknessVariation;  // the default look, swirls and all
  const EnvironmentImage sky = neutralSky();
  Renderer renderer(device, o, sky);
  const WithAndWithoutFilm drawn = drawWithAndWithoutFilm(renderer, frames.midStroke, frames.midStrokeCamera);
  writePng("render_mid_stroke.png", kWidth, kHeight, drawn.with);
  printWhereTheColourComesFrom(frames.midStroke, frames.midStrokeCamera, sky, drawn);
  double sum = 0;
  size_t pixels = 0;
  for (size_t p = 0; p < drawn.with.size() / 3; ++p) {
    if (drawn.change(p) <= 2) continue;
    sum += saturation(&drawn.with[3 * p]);
    ++pixels;
  }
  const double meanSaturation = pixels ? sum / static_cast<double>(pixels) : 0.0;
  std::printf("mid-stroke: %zu film pixels (%.0f%% of the image), mean saturation %.3f\n", pixels,
              100.0 * static_cast<double>(pixels) / (kWidth * kHeight), meanSaturation);
  EXPECT_GT(meanSaturation, 0.1);
  EXPECT_EQ(device->validationErrors(), 0u);
}

// The sky is drawn into an image of its own only when the view turns or zooms (the resolve reads it otherwise).
// The image's top rows show only sky in the known scene (its droplets' ring is below them): they must change when
// the view turns or zooms, stay when only the camera's place changes, and turning back must give the first
// picture again, to the bit.
TEST(Renderer, TheSkyIsDrawnAgainWhenTheViewTurns) {
  GB_REQUIRE_VULKAN(device);
  const test::KnownScene scene = test::makeKnownScene();
  Renderer renderer(device, smallImage(), skyEnvironment(256));  // the sky has clouds and a horizon to turn
  RenderFrame frame = test::frameOf(scene);
  auto drawn = [&](const OrbitCamera& camera) {
    frame.camera = camera;
    renderer.render(frame);
    return renderer.readPixels();
  };
  auto topRows = [](const std::vector<uint8_t>& rgb) {  // the top 16th: above the droplets' ring
    return std::vector<uint8_t>(rgb.begin(), rgb.begin() + 3 * kWidth * (kHeight / 16));
  };
  const OrbitCamera base = scene.camera;
  const std::vector<uint8_t> ahead = drawn(base);
  OrbitCamera turned = base, zoomed = base, moved = base;
  turned.yaw += 0.5f;
  zoomed.fovY *= 0.8f;
  moved.target += Vec3(0.0f, 0.05f, 0.0f);
  moved.distance += 0.2f;
  // Mean differences of a few levels at least: the sky's clouds and gradient move under the turn and the zoom.
  EXPECT_GT(compare(topRows(drawn(turned)), topRows(ahead)).mean, 1.0);
  EXPECT_GT(compare(topRows(drawn(zoomed)), topRows(ahead)).mean, 1.0);
  // The sky at infinity is the same from anywhere: its pixels stay to the bit (the film and props move).
  EXPECT_EQ(compare(topRows(drawn(moved)), topRows(ahead)).max, 0);
  EXPECT_EQ(compare(drawn(base), ahead).max, 0);
  EXPECT_EQ(device->validationErrors(), 0u);
}

TEST(Renderer, RejectsAbsurdImageSizes) {
  GB_REQUIRE_VULKAN(device);
  RenderOptions o = smallImage();
  o.width = 0;
  EXPECT_THROW(Renderer(device, o, studioEnvironment(64)), std::invalid_argument);
  EXPECT_THROW(colouringFromName("rainbow"), std::invalid_argument);
}

TEST(RenderOutput, EnvironmentPngIsDecodedToLinearRadiance) {
  // sRGB 128 is linear 0.2159 (IEC 61966-2-1); 255 is 1. Tolerance 1e-4: float rounding only.
  std::vector<uint8_t> rgb(64 * 32 * 3, 128);
  rgb[0] = 255;
  writePng("environment_test.png", 64, 32, rgb);
  const EnvironmentImage env = loadEnvironment("environment_test.png");
  ASSERT_EQ(env.width, 64);
  ASSERT_EQ(env.height, 32);
  EXPECT_NEAR(env.rgb[0], 1.0f, 1e-4f);
  EXPECT_NEAR(env.rgb[1], 0.2159f, 1e-4f);
  // An image that is not 2:1 cannot be an equirectangular panorama: refused with its size named.
  writePng("environment_square.png", 32, 32, std::vector<uint8_t>(32 * 32 * 3, 0));
  try {
    loadEnvironment("environment_square.png");
    ADD_FAILURE() << "a square environment was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("32x32"), std::string::npos) << e.what();
  }
}

TEST(RenderOutput, ACpuDriverDrawsWithoutMultisamplingUnlessAsked) {
  // Exact: a choice, not a measurement. Four samples cost lavapipe 1.6 times the main job's wall time
  // (docs/performance.md), so a CPU driver draws one; a GPU the image's four, and --samples always wins.
  RenderOutputOptions o;
  EXPECT_EQ(samplesFor(o, "CPU"), 1);
  EXPECT_EQ(samplesFor(o, "discrete GPU"), 4);
  EXPECT_EQ(samplesFor(o, "integrated GPU"), 4);
  o.samples = 4;
  EXPECT_EQ(samplesFor(o, "CPU"), 4);
  o.samples = 2;
  EXPECT_EQ(samplesFor(o, "discrete GPU"), 2);
}

}  // namespace
}  // namespace gb
