// The registration of depth pixels to the colour image: the factory constants and a recording's device.json.
#include "capture/colour_registration.h"

#include <gtest/gtest.h>

#include <string>

#include "capture/hand_source.h"
#include "capture/kinect_depth.h"

namespace gb {
namespace {

// libfreenect's registration as fakenect records it, with a Kinect v1's zero plane (2.4 cm between the cameras, a
// 120 mm reference distance, 0.1042 mm pixels); the fields this does not read are left out.
const char* const kDeviceJson = R"({
  "reg_info": {"ax": 0, "bx": 0},
  "zero_plane_info": {"dcmos_emitter_dist": 7.5, "dcmos_rcmos_dist": 2.4, "reference_distance": 120.0,
                      "reference_pixel_size": 0.1042},
  "const_shift": 200.0
})";

TEST(ColourRegistration, ADeviceJsonMapsTheDepthCentreToTheDocumentedColourPixel) {
  const ColourRegistration r = registrationFromDeviceJson(kDeviceJson, "device.json");
  // docs/formats.md's worked example: the depth image's principal point at 2 m is the camera-space point (0, 0, 2);
  // 2.4 cm to the side for the colour camera, at f = 120 / (2 x 0.1042) = 575.816 pixels: u = 328.943 + 575.816 x
  // 0.024 / 2 = 335.852, v = 267.481. Tolerance 1e-3 pixel: the arithmetic in doubles, far below a pixel.
  const std::optional<Eigen::Vector2d> c = r.colourPixel(kinect::kCx, kinect::kCy, 2.0);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->x(), 335.852, 1e-3);
  EXPECT_NEAR(c->y(), 267.481, 1e-3);
  // Nearer, the colour camera sees the point farther from its centre (the parallax of 2.4 cm at 1 m: 13.8 pixels).
  EXPECT_NEAR(r.colourPixel(kinect::kCx, kinect::kCy, 1.0)->x() - r.cx, 13.820, 1e-3);
}

TEST(ColourRegistration, TheFactoryConstantsMoveTheColourPixelByTheCamerasOffsetAndTurn) {
  // The colour camera 2 cm beside the depth camera and turned by about a degree: a depth pixel at 2 m is seen within
  // 20 colour pixels of where the colour camera's intrinsics alone would put it (1 degree is 9 pixels, 2 cm at 2 m is
  // 5); the bound catches axes swapped or a sign turned (40 pixels and more).
  const ColourRegistration r = factoryRegistration();
  for (const auto& [u, v] : {std::pair{320.0, 240.0}, {100.0, 100.0}, {540.0, 400.0}}) {
    const Eigen::Vector3d p = kinect::pixelToCamera(u, v, 2.0);
    const Eigen::Vector2d intrinsicsAlone(r.cx + r.fx * p.x() / p.z(), r.cy - r.fy * p.y() / p.z());
    const std::optional<Eigen::Vector2d> c = r.colourPixel(u, v, 2.0);
    ASSERT_TRUE(c);
    EXPECT_LT((*c - intrinsicsAlone).norm(), 20.0) << u << ", " << v;
  }
  // Parallax: a point at 1 m is seen fx T.x (1/1 - 1/2) = 5.3 pixels farther right than the same pixel at 2 m
  // (tolerance 1 pixel: the small turn moves the two a little differently).
  EXPECT_NEAR(r.colourPixel(320, 240, 1.0)->x() - r.colourPixel(320, 240, 2.0)->x(), r.fx * r.translation.x() * 0.5,
              1.0);
}

TEST(ColourRegistration, AMalformedDeviceJsonNamesTheField) {
  const auto error = [](const std::string& text) {
    try {
      registrationFromDeviceJson(text, "rec/device.json");
    } catch (const HandSourceError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(error("not json").find("rec/device.json: not a JSON object"), std::string::npos);
  EXPECT_NE(error(R"({"zero_plane_info": {}})").find("no zero_plane_info.dcmos_rcmos_dist"), std::string::npos);
  EXPECT_NE(error(R"({"zero_plane_info": {"dcmos_rcmos_dist": 2.4, "reference_distance": 120,
                       "reference_pixel_size": -1}})")
                .find("zero_plane_info.reference_pixel_size = -1 is outside"),
            std::string::npos);
}

}  // namespace
}  // namespace gb
