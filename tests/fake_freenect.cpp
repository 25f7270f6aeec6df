// A stand-in for the live libfreenect, for the tests of a Kinect unplugged mid-performance and plugged back in
// (giantbubble loads it through GIANTBUBBLE_FREENECT_LIBRARY). It serves one depth frame, 30 times a second,
// and holds the accelerometer level. Two environment variables steer it:
//   GB_FAKE_KINECT_FRAME        a fakenect depth file (one-line PGM header, then 640x480 little-endian raw)
//   GB_FAKE_KINECT_UNPLUGGED_IF a path: while a file is there the Kinect is unplugged (no device on the bus,
//                               and an open device's events fail as libusb's do, LIBUSB_ERROR_NO_DEVICE)
// Like the real one, a device that is open cannot be opened a second time (libusb: the interface is claimed)
// until it is closed.
#include <libfreenect.h>
#include <sys/stat.h>
#include <time.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace {

constexpr int kWidth = 640, kHeight = 480;
constexpr int kNoDevice = -4;  // LIBUSB_ERROR_NO_DEVICE

struct Fake {
  freenect_depth_cb depthCallback = nullptr;
  bool depthStarted = false;
  int openDevices = 0;
  double lastFrame = 0.0;
  uint32_t timestamp = 0;
  std::vector<uint16_t> depth = std::vector<uint16_t>(kWidth * kHeight, 2047);
  freenect_raw_tilt_state tilt{};
};
Fake fake;
int contextToken, deviceToken;  // their addresses stand for the context and the device

double now() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

bool unplugged() {
  const char* path = std::getenv("GB_FAKE_KINECT_UNPLUGGED_IF");
  struct stat st {};
  return path && ::stat(path, &st) == 0;
}

void loadFrame() {
  const char* path = std::getenv("GB_FAKE_KINECT_FRAME");
  if (!path) return;
  std::ifstream in(path, std::ios::binary);
  std::string header;
  std::getline(in, header);
  std::vector<unsigned char> bytes(2 * fake.depth.size());
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!in) return;
  for (size_t i = 0; i < fake.depth.size(); ++i)
    fake.depth[i] = static_cast<uint16_t>(bytes[2 * i] | bytes[2 * i + 1] << 8);
}

}  // namespace

extern "C" {

int freenect_init(freenect_context** ctx, freenect_usb_context*) {
  *ctx = reinterpret_cast<freenect_context*>(&contextToken);
  loadFrame();
  fake.tilt.accelerometer_y = FREENECT_COUNTS_PER_G;  // level
  return 0;
}
int freenect_shutdown(freenect_context*) { return 0; }
void freenect_set_log_level(freenect_context*, freenect_loglevel) {}
void freenect_select_subdevices(freenect_context*, freenect_device_flags) {}
int freenect_num_devices(freenect_context*) { return unplugged() ? 0 : 1; }
int freenect_open_device(freenect_context*, freenect_device** dev, int index) {
  if (index != 0 || unplugged() || fake.openDevices > 0) return -1;
  ++fake.openDevices;
  *dev = reinterpret_cast<freenect_device*>(&deviceToken);
  return 0;
}
int freenect_close_device(freenect_device*) {
  --fake.openDevices;
  fake.depthStarted = false;
  return 0;
}
freenect_frame_mode freenect_find_depth_mode(freenect_resolution res, freenect_depth_format fmt) {
  freenect_frame_mode mode{};
  mode.resolution = res;
  mode.depth_format = fmt;
  mode.bytes = kWidth * kHeight * 2;
  mode.width = kWidth;
  mode.height = kHeight;
  mode.data_bits_per_pixel = 11;
  mode.framerate = 30;
  mode.is_valid = 1;
  return mode;
}
int freenect_set_depth_mode(freenect_device*, const freenect_frame_mode) { return 0; }
void freenect_set_depth_callback(freenect_device*, freenect_depth_cb cb) { fake.depthCallback = cb; }
int freenect_start_depth(freenect_device*) {
  fake.depthStarted = true;
  return 0;
}
int freenect_stop_depth(freenect_device*) {
  fake.depthStarted = false;
  return 0;
}
// One frame per 1/30 s: waits for the next one up to the timeout, as libusb's event loop would.
int freenect_process_events_timeout(freenect_context*, timeval* timeout) {
  if (unplugged()) return kNoDevice;
  const double limit =
      timeout ? static_cast<double>(timeout->tv_sec) + 1e-6 * static_cast<double>(timeout->tv_usec) : 1.0;
  const double due = fake.lastFrame + 1.0 / 30.0, start = now();
  const double wait = std::min(std::max(due - start, 0.0), limit);
  const timespec pause{static_cast<time_t>(wait),
                       static_cast<long>((wait - static_cast<double>(static_cast<time_t>(wait))) * 1e9)};
  nanosleep(&pause, nullptr);
  if (now() < due || !fake.depthStarted || !fake.depthCallback) return 0;
  fake.lastFrame = now();
  fake.depthCallback(reinterpret_cast<freenect_device*>(&deviceToken), fake.depth.data(), fake.timestamp++);
  return 0;
}
int freenect_update_tilt_state(freenect_device*) { return unplugged() ? kNoDevice : 0; }
freenect_raw_tilt_state* freenect_get_tilt_state(freenect_device*) { return &fake.tilt; }
void freenect_get_mks_accel(freenect_raw_tilt_state* state, double* x, double* y, double* z) {
  constexpr double g = 9.80665;
  *x = state->accelerometer_x * g / FREENECT_COUNTS_PER_G;
  *y = state->accelerometer_y * g / FREENECT_COUNTS_PER_G;
  *z = state->accelerometer_z * g / FREENECT_COUNTS_PER_G;
}

}  // extern "C"
