#pragma once
// Kinect v1 depth geometry: raw 11-bit disparity to metres, and depth pixels to 3D camera space.
//
// Camera space (used by every hand source): x to the right of the depth image, y up, z away from the camera
// along the optical axis, in metres. A pixel (u, v) (u to the right, v down, origin top left) at depth z is
//   x = (u - cx) z / fx,   y = -(v - cy) z / fy.
//
// Both sets of constants are published fits for the Kinect v1 that libfreenect users rely on; the Kinect's
// own calibration is not read (Debian's fakenect cannot replay it). See docs/capture.md.

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace gb {
struct ColourRegistration;  // colour_registration.h
}

namespace gb::kinect {

constexpr int kWidth = 640;  // FREENECT_RESOLUTION_MEDIUM depth frame
constexpr int kHeight = 480;
constexpr int kPixels = kWidth * kHeight;
constexpr int kColourBytes = kPixels * 3;  // FREENECT_VIDEO_RGB at FREENECT_RESOLUTION_MEDIUM: 640x480, 8 bits each
constexpr uint16_t kNoReading = 2047;      // raw value of a pixel without a depth reading

// Depth intrinsics from Nicolas Burrus' Kinect v1 calibration (fx_d, fy_d, cx_d, cy_d of his published
// calibration file); lens distortion is ignored (under a pixel at the frame centre, a few at the corners).
constexpr double kFx = 594.21434211923247;
constexpr double kFy = 591.04053696870778;
constexpr double kCx = 339.30780975300314;
constexpr double kCy = 242.73913761751615;

// Raw disparity to metres, Stéphane Magnenat's fit on the OpenKinect wiki ("Imaging Information"):
//   z = 0.1236 tan(raw / 2842.5 + 1.1863) m.
// It tracks the ROS calibration data more closely than the 1 / (a raw + b) fit over the working range.
constexpr double kTanScale = 0.1236, kTanDivisor = 2842.5, kTanOffset = 1.1863;
// Raw values at and beyond this one are out of range: the fit climbs past 10 m and diverges at raw 1092.
constexpr uint16_t kFarthestRaw = 1056;

// Metres for a raw value; 0 for no reading (raw 2047 and the diverging end of the fit).
double rawToMetres(uint16_t raw);
// The raw value whose depth is nearest to z (m); kNoReading outside the range of the fit. For synthetic frames.
uint16_t metresToRaw(double z);

// The 2048-entry table the detector uses, rawToMetres for every raw value.
const std::array<float, 2048>& depthTable();

Eigen::Vector3d pixelToCamera(double u, double v, double z);
// Pixel coordinates (u, v) of a camera-space point in front of the camera.
Eigen::Vector2d cameraToPixel(const Eigen::Vector3d& p);

// The accelerometer (libfreenect's tilt state, in m/s^2 from freenect_get_mks_accel; raw counts are 819 per g)
// reads the reaction to gravity, i.e. "up", in the Kinect's own axes: x to the Kinect's left as it looks out, y up, z
// forward along the optical axis. In camera space (x right, y up, z forward) up is (-x, y, z), normalised.
// Nothing for a reading that is not about 1 g (0.5-1.5 g: the Kinect being moved) or that puts up more than
// 60 degrees from the camera's y axis (a Kinect on its side or upside down, or axes read wrongly): the floor
// is then searched for instead.
std::optional<Eigen::Vector3d> accelToCameraUp(double ax, double ay, double az);
// The raw accelerometer counts of a camera-space up direction (1 g), for synthetic recordings.
std::array<int16_t, 3> cameraUpToAccel(const Eigen::Vector3d& up);
constexpr double kAccelCountsPerG = 819.0;    // FREENECT_COUNTS_PER_G
constexpr double kStandardGravity = 9.80665;  // m/s^2, libfreenect's GRAVITY

// One depth frame: raw 11-bit disparities, row-major, kWidth x kHeight.
struct DepthFrame {
  double time = 0.0;       // seconds since the stream started (recording: from the file name)
  uint32_t timestamp = 0;  // the Kinect's own frame counter (fakenect keeps it in the file name)
  std::vector<uint16_t> raw = std::vector<uint16_t>(kPixels, kNoReading);
  // The direction against gravity in camera space, from the accelerometer, when the input carries it.
  std::optional<Eigen::Vector3d> gravityUp;
  // The colour camera's newest image (kColourBytes of RGB, rows from the top), when the input has one; else empty.
  std::vector<uint8_t> colour;
  // How the depth pixels map into it: the device's registration or the factory constants (with `colour` only).
  std::shared_ptr<const ColourRegistration> registration;
};

}  // namespace gb::kinect
