// The mirror view: the depth camera's view of the world (its intrinsics, where the calibration puts it, mirrored),
// what it draws of a depth frame, and on lavapipe the depth test between the camera image and the film.
#include "app/show/mirror_view.h"

#include <gtest/gtest.h>

#include "capture/colour_registration.h"
#include "tests/test_films.h"
#include "tests/vulkan_test_device.h"

namespace gb {
namespace {

Calibration tiltedCalibration() {
  Calibration c;
  c.cameraPitch = 12.0;
  c.reach = 2.0;
  c.performer = Vec3d(0.1, -0.2, 2.2);
  return c;
}

// Where a world point lands in a picture of width x height drawn with `view`, and which camera image pixel that is.
Eigen::Vector2f imagePixelOf(const DepthCameraView& view, const Vec3& world, int width, int height, float* depth) {
  const Eigen::Vector4f clip =
      view.viewProjection(static_cast<float>(width) / static_cast<float>(height)) * world.homogeneous();
  const Eigen::Vector2f picture((clip.x() / clip.w() + 1.0f) * 0.5f * static_cast<float>(width),
                                (clip.y() / clip.w() + 1.0f) * 0.5f * static_cast<float>(height));
  if (depth) *depth = clip.z() / clip.w();
  const Eigen::Vector4f map = view.imageOfPicture(width, height);
  return {map.x() * picture.x() + map.y(), map.z() * picture.y() + map.w()};
}

TEST(MirrorView, AWorldPointIsDrawnAtItsDepthPixelMirroredAndAtItsDepth) {
  const Calibration calibration = tiltedCalibration();
  const DepthCameraView view = mirrorCamera(calibration);
  // Camera-space points seen by the depth camera, carried into the world as the hands are: the picture shows each
  // at its own depth pixel (tolerance 0.01 pixel: float arithmetic on world coordinates of a few metres), at the
  // depth buffer's value of its distance (1e-5 of the depth range).
  for (const Vec3d& p : {Vec3d(0.3, 0.4, 1.5), Vec3d(-0.8, -0.5, 3.0), Vec3d(0.0, 0.0, 2.2)}) {
    float depth = 0.0f;
    const Eigen::Vector2f pixel = imagePixelOf(view, calibration.toWorld(p).cast<float>(), 960, 540, &depth);
    const Eigen::Vector2d expected = kinect::cameraToPixel(p);
    EXPECT_NEAR(pixel.x(), expected.x(), 0.01) << p.transpose();
    EXPECT_NEAR(pixel.y(), expected.y(), 0.01) << p.transpose();
    EXPECT_NEAR(depth, view.clipDepth(static_cast<float>(p.z())), 1e-5) << p.transpose();
  }
  // Mirrored: what is on the camera's right (+x, the performer's left) is on the picture's left.
  const Eigen::Vector4f clip =
      view.viewProjection(16.0f / 9.0f) * calibration.toWorld(Vec3d(0.5, 0.0, 2.0)).cast<float>().homogeneous();
  EXPECT_LT(clip.x() / clip.w(), 0.0f);
  // The eye is where the calibration puts the camera (1e-5 m).
  EXPECT_LT((view.eye() - calibration.toWorld(Vec3d::Zero()).cast<float>()).norm(), 1e-5f);
}

// A frame at 3 m with a block at 2 m that the segmentation took for the performer.
kinect::DepthFrame frameWithBlock(BodyDepth& body) {
  kinect::DepthFrame frame;
  for (uint16_t& raw : frame.raw) raw = kinect::metresToRaw(3.0);
  for (int v = 200; v < 300; ++v)
    for (int u = 300; u < 360; ++u) frame.raw[static_cast<size_t>(v) * kinect::kWidth + u] = kinect::metresToRaw(2.0);
  for (int v = 100; v < 150; ++v)
    for (int u = 150; u < 180; ++u) body.depth[static_cast<size_t>(v) * BodyDepth::kWidth + u] = 2.0f;
  return frame;
}

TEST(MirrorView, TheCameraImageIsThePerformerAloneOrTheRoomToo) {
  BodyDepth body;
  const kinect::DepthFrame frame = frameWithBlock(body);
  const CameraImage performer = cameraImageOf(frame, body, false);
  const size_t inside = 250 * kinect::kWidth + 330, outside = 50 * kinect::kWidth + 50;
  EXPECT_NEAR(performer.depth[inside], 2.0f, 0.01f);  // the raw value's step at 2 m: 6 mm
  EXPECT_EQ(performer.depth[outside], 0.0f);
  EXPECT_EQ(performer.rgba[inside] >> 24, 255u);
  const CameraImage room = cameraImageOf(frame, body, true);
  EXPECT_NEAR(room.depth[outside], 3.0f, 0.03f);          // the step at 3 m: 15 mm
  EXPECT_NE(room.rgba[outside], performer.rgba[inside]);  // the room grey, the performer a warm silhouette
}

TEST(MirrorView, AColourFrameColoursThePerformerByItsRegisteredPixels) {
  BodyDepth body;
  kinect::DepthFrame frame = frameWithBlock(body);
  frame.colour.assign(static_cast<size_t>(kinect::kColourBytes), 0);
  for (size_t i = 0; i < frame.colour.size(); i += 3) frame.colour[i + 1] = 200;  // green everywhere
  frame.registration = std::make_shared<const ColourRegistration>(factoryRegistration());
  const CameraImage image = cameraImageOf(frame, body, false);
  const uint32_t c = image.rgba[250 * kinect::kWidth + 330];
  EXPECT_EQ(c & 0xff, 0u);
  EXPECT_EQ((c >> 8) & 0xff, 200u);
  EXPECT_EQ((c >> 16) & 0xff, 0u);
}

// The camera image of two patches of the same size, one in front of a film and one behind it.
CameraImage twoPatches(float nearDepth, float farDepth) {
  CameraImage image;
  image.width = kinect::kWidth;
  image.height = kinect::kHeight;
  image.depth.assign(static_cast<size_t>(kinect::kPixels), 0.0f);
  image.rgba.assign(static_cast<size_t>(kinect::kPixels), 0u);
  for (int v = 180; v < 300; ++v)
    for (int u = 40; u < 160; ++u) {
      const size_t left = static_cast<size_t>(v) * kinect::kWidth + u, right = left + 440;
      image.depth[left] = nearDepth;
      image.rgba[left] = 0xff00c000u;  // green
      image.depth[right] = farDepth;
      image.rgba[right] = 0xffc00000u;  // blue
    }
  return image;
}

TEST(MirrorView, AHandInFrontOfTheFilmCoversItAndTheFilmInFrontOfTheBodyCoversIt) {
  GB_REQUIRE_VULKAN(device);
  // The default calibration's camera stands 4 m in front of the anchor looking back at it: a film in the world's
  // plane z = 0 is 2 m away in camera space. A green patch at 1.5 m is in front of it, a blue one at 2.5 m behind.
  const Calibration calibration;
  const DepthCameraView view = mirrorCamera(calibration);
  const Params params;
  Film film = test::makeFilm(
      params, {{-3.0f, -1.0f, 0.0f}, {3.0f, -1.0f, 0.0f}, {3.0f, 4.0f, 0.0f}, {-3.0f, 4.0f, 0.0f}}, {0, 1, 2, 0, 2, 3});
  for (size_t i = 0; i < film.state.size(); ++i) {
    film.state.thickness[i] = 200e-9f;  // first-order magenta
    film.state.normal.set(i, Vec3::UnitZ());
  }
  const Film noFilm;
  const CameraImage image = twoPatches(1.5f, 2.5f);
  RenderOptions options;
  options.width = 240;
  options.height = 160;
  options.thicknessVariation = 0.0f;
  Renderer renderer(device, options, studioEnvironment(64));
  const auto draw = [&](const Film& f) {
    RenderFrame frame;
    frame.film = &f;
    frame.mirror = &view;
    frame.cameraImage = &image;
    renderer.render(frame);
    return renderer.readPixels();
  };
  const std::vector<uint8_t> bare = draw(noFilm), filmed = draw(film);
  // Image pixel (100, 240), the green patch, is drawn mirrored on the picture's right: X = 120 + (320 - 100) / 3
  // = 193; the blue patch's (540, 240) on its left, X = 47; both at Y = 80.
  const auto at = [](const std::vector<uint8_t>& rgb, int x, int y, int c) {
    return static_cast<int>(rgb[3 * (static_cast<size_t>(y) * 240 + static_cast<size_t>(x)) + static_cast<size_t>(c)]);
  };
  EXPECT_GT(at(bare, 193, 80, 1), 150);  // green
  EXPECT_LT(at(bare, 193, 80, 2), 30);
  EXPECT_GT(at(bare, 47, 80, 2), 150);  // blue
  EXPECT_LT(at(bare, 47, 80, 1), 30);
  // In front of the film the patch is as it is without the film (tolerance 1 level: the same pixels, drawn alike);
  // behind it, the film's reflection and tint change it by far more than that (at least 10 levels in a channel).
  int nearChange = 0, farChange = 0;
  for (int c = 0; c < 3; ++c) {
    nearChange = std::max(nearChange, std::abs(at(filmed, 193, 80, c) - at(bare, 193, 80, c)));
    farChange = std::max(farChange, std::abs(at(filmed, 47, 80, c) - at(bare, 47, 80, c)));
  }
  EXPECT_LE(nearChange, 1);
  EXPECT_GE(farChange, 10);
  EXPECT_EQ(device->validationErrors(), 0u);
}

}  // namespace
}  // namespace gb
