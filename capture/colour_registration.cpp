#include "capture/colour_registration.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "capture/hand_source.h"
#include "capture/kinect_depth.h"
#include "capture/untrusted.h"

namespace gb {

std::optional<Eigen::Vector2d> ColourRegistration::colourPixel(double u, double v, double z) const {
  const Eigen::Vector3d p = kinect::pixelToCamera(u, v, z);
  const Eigen::Vector3d q = rotation * Eigen::Vector3d(p.x(), -p.y(), p.z()) + translation;
  if (!(q.z() > 0.0)) return std::nullopt;
  return Eigen::Vector2d(cx + fx * q.x() / q.z(), cy + fy * q.y() / q.z());
}

ColourRegistration factoryRegistration() {
  ColourRegistration r;
  // fx_rgb, fy_rgb, cx_rgb, cy_rgb, R and T of Burrus' published Kinect v1 calibration file.
  r.fx = 529.21508098293293;
  r.fy = 525.56393630057437;
  r.cx = 328.94272028759258;
  r.cy = 267.48068171871557;
  r.rotation << 0.99984628826577793, 0.0012635359098409581, -0.017487233004436643,  //
      -0.0014779096108364480, 0.99992385683542895, -0.012251380107679535,           //
      0.017470421412464927, 0.012275341476520762, 0.99977202419716948;
  r.translation = Eigen::Vector3d(0.019985242312092553, -0.00074423738761617583, -0.010916736334336222);
  r.source = "factory constants";
  return r;
}

namespace {

// A number of device.json's `group` that must lie in [low, high].
double field(const nlohmann::json& root, const char* group, const char* name, double low, double high,
             const std::string& where) {
  const std::string key = std::string(group) + "." + name;
  if (!root.contains(group) || !root[group].is_object() || !root[group].contains(name))
    throw HandSourceError(where + ": no " + key + " (libfreenect's registration as fakenect records it)");
  const nlohmann::json& value = root[group][name];
  if (!value.is_number()) throw HandSourceError(where + ": " + key + " is not a number");
  const double x = value.get<double>();
  if (!(x >= low && x <= high)) {
    std::ostringstream text;
    text << where << ": " << key << " = " << x << " is outside " << low << ".." << high;
    throw HandSourceError(text.str());
  }
  return x;
}

}  // namespace

ColourRegistration registrationFromDeviceJson(const std::string& text, const std::string& where) {
  const nlohmann::json root = nlohmann::json::parse(text, nullptr, false);
  if (root.is_discarded() || !root.is_object()) throw HandSourceError(where + ": not a JSON object");
  // Ranges wide around a Kinect v1's (2.4 cm, 120 mm, 0.1042 mm): what lies outside is not a Kinect's.
  const double baseline = field(root, "zero_plane_info", "dcmos_rcmos_dist", 0.5, 10.0, where);        // cm
  const double reference = field(root, "zero_plane_info", "reference_distance", 10.0, 1000.0, where);  // mm
  const double pixel = field(root, "zero_plane_info", "reference_pixel_size", 0.01, 1.0, where);       // mm
  ColourRegistration r = factoryRegistration();
  r.fx = r.fy = reference / (2.0 * pixel);
  r.rotation.setIdentity();
  r.translation = Eigen::Vector3d(baseline / 100.0, 0.0, 0.0);
  r.source = where;
  r.deviceJson = text;
  return r;
}

ColourRegistration recordingRegistration(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / "device.json";
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return factoryRegistration();
  const std::string where = printablePath(file);
  if (const std::string why = whyNotARegularFile(file); !why.empty()) throw HandSourceError(where + " " + why);
  constexpr std::uintmax_t kMaxBytes = 1 << 20;  // libfreenect's registration is about 1 KB of JSON
  if (std::filesystem::file_size(file, ec) > kMaxBytes) throw HandSourceError(where + " is larger than 1 MiB");
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return registrationFromDeviceJson(text.str(), where);
}

std::vector<uint8_t> registeredColour(const std::vector<uint8_t>& colour, const std::vector<float>& depth,
                                      const ColourRegistration& registration) {
  std::vector<uint8_t> out(static_cast<size_t>(kinect::kPixels) * 3, 0);
  for (int v = 0; v < kinect::kHeight; ++v)
    for (int u = 0; u < kinect::kWidth; ++u) {
      const size_t i = static_cast<size_t>(v) * kinect::kWidth + static_cast<size_t>(u);
      if (!(depth[i] > 0.0f)) continue;
      const std::optional<Eigen::Vector2d> c = registration.colourPixel(u, v, depth[i]);
      if (!c) continue;
      const long cu = std::lround(c->x()), cv = std::lround(c->y());
      if (cu < 0 || cv < 0 || cu >= kinect::kWidth || cv >= kinect::kHeight) continue;
      const size_t j = static_cast<size_t>(cv) * kinect::kWidth + static_cast<size_t>(cu);
      for (size_t k = 0; k < 3; ++k) out[3 * i + k] = colour[3 * j + k];
    }
  return out;
}

}  // namespace gb
