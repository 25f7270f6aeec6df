#pragma once
// Where a depth pixel is seen in the Kinect v1's colour image: the two cameras as a pinhole pair. A depth pixel (u, v)
// at depth z is the camera-space point p (kinect_depth.h); the colour camera sees it at
//   q = R p' + T,   p' = (p.x, -p.y, p.z)   (its image's axes: x right, y down, z forward)
//   (u_c, v_c) = (cx + fx q.x / q.z,  cy + fy q.y / q.z)   in its 640x480 image.
// The factory constants are Nicolas Burrus' calibration of a Kinect v1 (the same fit as the depth intrinsics in
// kinect_depth.h). A recording's device.json (fakenect's record of libfreenect's freenect_registration) gives the
// device's own distance between the two cameras (zero_plane_info.dcmos_rcmos_dist) and focal length
// (reference_distance / reference_pixel_size, a pixel of the 1280-wide sensor being half one of the 640-wide image):
// then R is the identity, T = (dcmos_rcmos_dist, 0, 0) and the principal point is the factory one. docs/formats.md
// has the file and a worked example.

#include <Eigen/Dense>
#include <filesystem>
#include <optional>
#include <string>

namespace gb {

struct ColourRegistration {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;  // colour image intrinsics (pixels)
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // m, depth camera -> colour camera, image axes
  std::string source;                                     // "factory constants" or the device.json it came from
  std::string deviceJson;                                 // that file's text (a recording made of it keeps it)

  // The colour pixel (u, v) of depth pixel (u, v) at depth z (m); nothing behind the colour camera.
  [[nodiscard]] std::optional<Eigen::Vector2d> colourPixel(double u, double v, double z) const;
};

// Burrus' calibration.
ColourRegistration factoryRegistration();

// The registration of device.json's text (libfreenect's registration as fakenect records it). Throws
// HandSourceError naming `where` and the field that is missing or out of range.
ColourRegistration registrationFromDeviceJson(const std::string& text, const std::string& where);

// A recording folder's device.json when it has one, else the factory constants.
ColourRegistration recordingRegistration(const std::filesystem::path& folder);

// The colour image (640x480 RGB, rows from the top) seen at each depth pixel of `depth` (metres per pixel, 0: no
// reading), as 640x480 RGB; black where the colour image does not reach or there is no reading.
std::vector<uint8_t> registeredColour(const std::vector<uint8_t>& colour, const std::vector<float>& depth,
                                      const ColourRegistration& registration);

}  // namespace gb
