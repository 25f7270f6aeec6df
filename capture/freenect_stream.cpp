#include "capture/freenect_stream.h"

#include <dlfcn.h>
#include <libfreenect.h>
#include <libfreenect_registration.h>
#include <sys/time.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "capture/colour_registration.h"
#include "capture/hand_source.h"
#include "capture/output_file.h"
#include "capture/untrusted.h"

#ifndef GB_FREENECT_LIBRARY
#define GB_FREENECT_LIBRARY "libfreenect.so.0.5"
#endif
#ifndef GB_FAKENECT_LIBRARY
#define GB_FAKENECT_LIBRARY "/usr/lib/x86_64-linux-gnu/fakenect/libfreenect.so.0.5"
#endif

namespace gb {

namespace fs = std::filesystem;

namespace {

constexpr size_t kDepthBytes = static_cast<size_t>(kinect::kPixels) * 2;

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Bytes after the one-line header of a depth file, or -1 when there is no header line; `header` gets the line.
long long depthPayload(const fs::path& file, std::string& header) {
  std::ifstream in(file, std::ios::binary);
  if (!in || !std::getline(in, header) || in.eof() || header.size() > 64) return -1;
  return static_cast<long long>(fs::file_size(file)) - static_cast<long long>(header.size() + 1);
}

// fakenect reads the frame as 640x480 big-endian 16-bit depth whatever the header says: a header that says
// anything else is a file of some other kind.
bool isKinectDepthHeader(const std::string& header) {
  std::istringstream in(header);
  std::string magic;
  int width = 0, height = 0, maxValue = 0;
  return (in >> magic >> width >> height >> maxValue) && (in >> std::ws).eof() && magic == "P5" &&
         width == kinect::kWidth && height == kinect::kHeight && maxValue > 255 && maxValue <= 65535;
}

// fakenect reads a colour entry as 640x480 8-bit RGB after a one-line header, whatever the header says.
bool isKinectColourHeader(const std::string& header) {
  std::istringstream in(header);
  std::string magic;
  int width = 0, height = 0, maxValue = 0;
  return (in >> magic >> width >> height >> maxValue) && (in >> std::ws).eof() && magic == "P6" &&
         width == kinect::kWidth && height == kinect::kHeight && maxValue == 255;
}

// Why fakenect could not read this entry's file now (empty when it can). The file's name comes from INDEX.txt: it is
// quoted escaped (printable).
std::string fileProblem(const fs::path& folder, const FakenectEntry& e) {
  const fs::path path = folder / e.file;
  const std::string shown = printablePath(path);
  // Checked, not opened: a FIFO would block playback and /dev/zero would never end.
  if (const std::string why = whyNotARegularFile(path); !why.empty()) return "file " + shown + " " + why;
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec || size == 0) return "file " + shown + " is empty";
  // fakenect reads an accelerometer entry as libfreenect's tilt state whole: a shorter file is read past its end.
  if (e.type == 'a' && size != sizeof(freenect_raw_tilt_state))
    return "accelerometer file " + shown + " is " + std::to_string(size) + " bytes, expected " +
           std::to_string(sizeof(freenect_raw_tilt_state)) + " (libfreenect's tilt state)";
  std::string header;
  const long long payload = depthPayload(path, header);
  if (e.type == 'r') {
    if (payload < 0 || !isKinectColourHeader(header))
      return "colour file " + shown + " has the header '" + printable(header) + "', expected 'P6 640 480 255'";
    if (payload < static_cast<long long>(kinect::kColourBytes))
      return "colour file " + shown + " is truncated: " + std::to_string(payload) + " bytes of colour, expected " +
             std::to_string(kinect::kColourBytes) + " (640x480 RGB)";
    return {};
  }
  if (e.type != 'd') return {};
  if (payload < 0) return "depth file " + shown + " has no one-line PGM header";
  if (!isKinectDepthHeader(header))
    return "depth file " + shown + " has the header '" + printable(header) + "', expected 'P5 640 480 65535'";
  if (payload < static_cast<long long>(kDepthBytes))
    return "depth file " + shown + " is truncated: " + std::to_string(payload) + " bytes of depth, expected " +
           std::to_string(kDepthBytes) + " (640x480 16-bit values)";
  return {};
}

}  // namespace

FakenectIndex readFakenectIndex(const fs::path& folder) {
  const std::string where = "fakenect recording " + printablePath(folder);
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    const std::string why = whyNotARegularFile(folder);
    throw HandSourceError(where + ": " + (why.empty() ? "is a file, not a folder" : why));
  }
  const fs::path indexFile = folder / "INDEX.txt";
  if (!fs::exists(indexFile, ec) && !ec)
    throw HandSourceError(where + ": no INDEX.txt (not a recording made by fakenect-record or giantbubble record)");
  std::string why;
  const InputFile in = openInputFile(indexFile, kMaxIndexBytes, why);
  if (!in) throw HandSourceError(where + ": INDEX.txt " + why + " (a recording of hours is a few MiB)");
  FakenectIndex index;
  index.folder = folder;
  std::string line;
  int lineNumber = 0, blankLine = 0, atOneTime = 0;
  double lastDepthTime = 0.0;
  for (LineRead read; (read = readLine(in.get(), line, kMaxIndexLineBytes)) != LineRead::End;) {
    ++lineNumber;
    if (read == LineRead::TooLong)
      throw HandSourceError(where + ", INDEX.txt line " + std::to_string(lineNumber) + ": longer than " +
                            std::to_string(kMaxIndexLineBytes) + " bytes (an entry is a file name)");
    if (line.empty()) {  // fakenect stops reading at an empty line
      if (!blankLine) blankLine = lineNumber;
      continue;
    }
    const std::string at = where + ", INDEX.txt line " + std::to_string(lineNumber);
    if (line.back() == '\r')
      throw HandSourceError(at + ": the line ends in a carriage return (CR LF line endings); fakenect reads LF only");
    if (blankLine)
      throw HandSourceError(at + ": entries after the empty line " + std::to_string(blankLine) +
                            " (fakenect stops there)");
    FakenectEntry e;
    unsigned int timestamp = 0;
    int used = 0;
    if (std::sscanf(line.c_str(), "%c-%lf-%u%n", &e.type, &e.time, &timestamp, &used) != 3 ||
        (e.type != 'd' && e.type != 'r' && e.type != 'a') || !std::isfinite(e.time))
      throw HandSourceError(at + ": '" + printable(line) +
                            "' is not a fakenect entry (TYPE-TIME-TIMESTAMP…, TYPE d, r or a)");
    const std::string time = printableNumber(line.substr(2, line.find('-', 2) - 2));  // as written
    // fakenect sleeps through the time between entries: a jump forward would stall playback for as long.
    if (!index.entries.empty() && e.time - index.entries.back().time > kMaxFakenectGap) {
      char jump[32];
      std::snprintf(jump, sizeof jump, "%.4g", e.time - index.entries.back().time);
      throw HandSourceError(at + ": time " + time + " jumps " + jump +
                            " s forward (fakenect would sleep through it; at most " +
                            std::to_string(static_cast<int>(kMaxFakenectGap)) + " s between entries)");
    }
    // A time that does not advance: a recording's frames, each a file fakenect reads, played as one moment.
    atOneTime = !index.entries.empty() && e.time == index.entries.back().time ? atOneTime + 1 : 1;
    if (atOneTime > kMaxEntriesAtOneTime)
      throw HandSourceError(at + ": " + std::to_string(atOneTime) + " entries at time " + time +
                            " (the time does not advance; fakenect-record writes at most a depth frame, a colour "
                            "image and an accelerometer reading at one time)");
    e.timestamp = timestamp;
    e.file = line;
    if (const std::string problem = fileProblem(folder, e); !problem.empty())
      throw HandSourceError(at + ": " + problem);
    if (e.type == 'd') {
      if (index.depthFrames > 0 && e.time <= lastDepthTime)
        throw HandSourceError(at + ": time " + time + " is not after the previous depth frame's");
      lastDepthTime = e.time;
      ++index.depthFrames;
    }
    index.entries.push_back(e);
  }
  if (index.depthFrames == 0) throw HandSourceError(where + ": empty recording (no depth frames in INDEX.txt)");
  return index;
}

FakenectWriter::FakenectWriter(const fs::path& folder) : folder_(folder) {
  std::error_code ec;
  if (fs::exists(folder, ec) && !(fs::is_directory(folder, ec) && fs::is_empty(folder, ec)))
    throw HandSourceError("will not record into " + printablePath(folder) + ": it exists and is not an empty folder");
  fs::create_directories(folder, ec);
  if (ec) throw HandSourceError("cannot create " + printablePath(folder) + ": " + ec.message());
}

void FakenectWriter::write(const kinect::DepthFrame& frame, double recordTime) {
  if (frame.gravityUp) writeAccelerometer(*frame.gravityUp, frame.timestamp, recordTime);
  if (frame.colour.size() == static_cast<size_t>(kinect::kColourBytes)) writeColour(frame, recordTime);
  char name[96];
  std::snprintf(name, sizeof name, "d-%f-%" PRIu32 ".pgm", recordTime, frame.timestamp);
  std::string bytes = "P5 " + std::to_string(kinect::kWidth) + ' ' + std::to_string(kinect::kHeight) + " 65535\n";
  const size_t header = bytes.size();
  bytes.resize(header + kDepthBytes);
  for (size_t i = 0; i < frame.raw.size(); ++i) {  // little-endian, what libfreenect hands out on x86 and ARM
    bytes[header + 2 * i] = static_cast<char>(frame.raw[i] & 0xff);
    bytes[header + 2 * i + 1] = static_cast<char>(frame.raw[i] >> 8);
  }
  writeFileAtomically(folder_ / name, bytes);
  addToIndex(name);
  ++frames_;
}

void FakenectWriter::writeColour(const kinect::DepthFrame& frame, double recordTime) {
  // The device's registration once, as fakenect-record keeps it beside the frames.
  if (!wroteRegistration_ && frame.registration && !frame.registration->deviceJson.empty()) {
    writeFileAtomically(folder_ / "device.json", frame.registration->deviceJson);
    wroteRegistration_ = true;
  }
  char name[96];
  std::snprintf(name, sizeof name, "r-%f-%" PRIu32 ".ppm", recordTime, frame.timestamp);
  std::string bytes = "P6 " + std::to_string(kinect::kWidth) + ' ' + std::to_string(kinect::kHeight) + " 255\n";
  bytes.append(frame.colour.begin(), frame.colour.end());
  writeFileAtomically(folder_ / name, bytes);
  addToIndex(name);
}

void FakenectWriter::writeAccelerometer(const Eigen::Vector3d& up, uint32_t timestamp, double recordTime) {
  // fakenect-record's 'a' entry: libfreenect's freenect_raw_tilt_state as it lies in memory.
  freenect_raw_tilt_state state{};
  const std::array<int16_t, 3> counts = kinect::cameraUpToAccel(up);
  state.accelerometer_x = counts[0];
  state.accelerometer_y = counts[1];
  state.accelerometer_z = counts[2];
  state.tilt_status = TILT_STATUS_STOPPED;
  char name[96];
  std::snprintf(name, sizeof name, "a-%f-%" PRIu32 ".dump", recordTime, timestamp);
  writeFileAtomically(folder_ / name, std::string_view(reinterpret_cast<const char*>(&state), sizeof state));
  addToIndex(name);
}

void FakenectWriter::addToIndex(const std::string& entry) {
  index_ += entry;
  index_ += '\n';
  writeFileAtomically(folder_ / "INDEX.txt", index_);
}

// One dlopen'ed libfreenect build and the device opened through it.
class FreenectLibrary {
 public:
  explicit FreenectLibrary(const std::string& path) {
    handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle_) throw HandSourceError("cannot load libfreenect (" + path + "): " + dlerror());
    bind(init, "freenect_init");
    bind(shutdown, "freenect_shutdown");
    bind(setLogLevel, "freenect_set_log_level");
    bind(selectSubdevices, "freenect_select_subdevices");
    bind(numDevices, "freenect_num_devices");
    bind(openDevice, "freenect_open_device");
    bind(closeDevice, "freenect_close_device");
    bind(findDepthMode, "freenect_find_depth_mode");
    bind(setDepthMode, "freenect_set_depth_mode");
    bind(setDepthCallback, "freenect_set_depth_callback");
    bind(startDepth, "freenect_start_depth");
    bind(stopDepth, "freenect_stop_depth");
    bind(processEvents, "freenect_process_events_timeout");
    bind(updateTiltState, "freenect_update_tilt_state");
    bind(getTiltState, "freenect_get_tilt_state");
    bind(getMksAccel, "freenect_get_mks_accel");
    // The colour stream, where the build has it (a stand-in library may not): without it, depth alone.
    bindIfThere(setVideoCallback, "freenect_set_video_callback");
    bindIfThere(findVideoMode, "freenect_find_video_mode");
    bindIfThere(setVideoMode, "freenect_set_video_mode");
    bindIfThere(startVideo, "freenect_start_video");
    bindIfThere(stopVideo, "freenect_stop_video");
    bindIfThere(copyRegistration, "freenect_copy_registration");
    bindIfThere(destroyRegistration, "freenect_destroy_registration");
  }
  ~FreenectLibrary() {
    if (device) {
      if (videoStarted) stopVideo(device);
      if (depthStarted) stopDepth(device);
      closeDevice(device);
    }
    if (context) shutdown(context);
    dlclose(handle_);  // unloads fakenect, so that the next recording starts from fresh globals
  }
  FreenectLibrary(const FreenectLibrary&) = delete;  // owns the dlopen handle
  FreenectLibrary& operator=(const FreenectLibrary&) = delete;

  // libfreenect calls back from inside process_events on the calling thread; this is the library being polled.
  static thread_local FreenectLibrary* polling;
  static void onDepth(freenect_device*, void* depth, uint32_t timestamp) {
    FreenectLibrary* self = polling;
    if (!self || !self->target) return;
    std::memcpy(self->target->raw.data(), depth, kDepthBytes);
    self->target->timestamp = timestamp;
    self->gotFrame = true;
  }
  static void onVideo(freenect_device*, void* rgb, uint32_t) {
    FreenectLibrary* self = polling;
    if (!self || !self->colourTarget) return;
    const auto* bytes = static_cast<const uint8_t*>(rgb);
    self->colourTarget->assign(bytes, bytes + kinect::kColourBytes);
  }

  // Initialises libfreenect and starts 11-bit depth on the first device; a message naming the failure otherwise.
  // The motor subdevice is opened too, for its accelerometer only (the tilt is never set); a Kinect whose motor
  // cannot be opened is used without it.
  void start(const std::string& what) {
    if (!open(what, static_cast<freenect_device_flags>(FREENECT_DEVICE_CAMERA | FREENECT_DEVICE_MOTOR))) {
      close();
      if (!open(what, FREENECT_DEVICE_CAMERA))
        throw HandSourceError("no Kinect found: the Kinect could not be opened (" + what +
                              "; permissions on /dev/bus/usb?)");
    } else {
      hasAccelerometer = true;
    }
    setDepthCallback(device, &FreenectLibrary::onDepth);
    const freenect_frame_mode mode = findDepthMode(FREENECT_RESOLUTION_MEDIUM, FREENECT_DEPTH_11BIT);
    if (!mode.is_valid || setDepthMode(device, mode) < 0 || startDepth(device) < 0)
      throw HandSourceError("the Kinect refused 640x480 11-bit depth (" + what + ")");
    depthStarted = true;
    startColour();
  }

  // 640x480 RGB video beside the depth, when the build has it; a camera that refuses it gives depth alone.
  void startColour() {
    if (!setVideoCallback || !findVideoMode || !setVideoMode || !startVideo || !stopVideo) return;
    setVideoCallback(device, &FreenectLibrary::onVideo);
    const freenect_frame_mode mode = findVideoMode(FREENECT_RESOLUTION_MEDIUM, FREENECT_VIDEO_RGB);
    videoStarted = mode.is_valid && setVideoMode(device, mode) >= 0 && startVideo(device) >= 0;
  }

  // The open device's registration as fakenect's device.json holds it (empty: the build cannot give it).
  std::string deviceJson() {
    if (!copyRegistration || !destroyRegistration) return {};
    freenect_registration r = copyRegistration(device);
    const freenect_reg_info& i = r.reg_info;
    nlohmann::json json;
    json["reg_info"] = {{"dx_center", i.dx_center},
                        {"ax", i.ax},
                        {"bx", i.bx},
                        {"cx", i.cx},
                        {"dx", i.dx},
                        {"dx_start", i.dx_start},
                        {"ay", i.ay},
                        {"by", i.by},
                        {"cy", i.cy},
                        {"dy", i.dy},
                        {"dy_start", i.dy_start},
                        {"dx_beta_start", i.dx_beta_start},
                        {"dy_beta_start", i.dy_beta_start},
                        {"rollout_blank", i.rollout_blank},
                        {"rollout_size", i.rollout_size},
                        {"dx_beta_inc", i.dx_beta_inc},
                        {"dy_beta_inc", i.dy_beta_inc},
                        {"dxdx_start", i.dxdx_start},
                        {"dxdy_start", i.dxdy_start},
                        {"dydx_start", i.dydx_start},
                        {"dydy_start", i.dydy_start},
                        {"dxdxdx_start", i.dxdxdx_start},
                        {"dydxdx_start", i.dydxdx_start},
                        {"dxdxdy_start", i.dxdxdy_start},
                        {"dydxdy_start", i.dydxdy_start},
                        {"back_comp1", i.back_comp1},
                        {"dydydx_start", i.dydydx_start},
                        {"back_comp2", i.back_comp2},
                        {"dydydy_start", i.dydydy_start}};
    json["reg_pad_info"] = {{"start_lines", r.reg_pad_info.start_lines},
                            {"end_lines", r.reg_pad_info.end_lines},
                            {"cropping_lines", r.reg_pad_info.cropping_lines}};
    const freenect_zero_plane_info& z = r.zero_plane_info;
    json["zero_plane_info"] = {{"dcmos_emitter_dist", z.dcmos_emitter_dist},
                               {"dcmos_rcmos_dist", z.dcmos_rcmos_dist},
                               {"reference_distance", z.reference_distance},
                               {"reference_pixel_size", z.reference_pixel_size}};
    json["const_shift"] = r.const_shift;
    destroyRegistration(&r);
    return json.dump(2);
  }

  // The accelerometer's up direction in camera space (kinect_depth.h), when it reads about 1 g.
  std::optional<Eigen::Vector3d> gravityUp() {
    double x = 0, y = 0, z = 0;
    freenect_raw_tilt_state* state = getTiltState(device);
    if (!state) return std::nullopt;
    getMksAccel(state, &x, &y, &z);
    return kinect::accelToCameraUp(x, y, z);
  }

  // One round of libfreenect events; true when a depth frame arrived into `frame`.
  bool pump(kinect::DepthFrame& frame, std::vector<uint8_t>& colour, double timeout, int& status) {
    timeval tv{static_cast<time_t>(timeout), static_cast<suseconds_t>(std::fmod(timeout, 1.0) * 1e6)};
    target = &frame;
    colourTarget = &colour;
    gotFrame = false;
    polling = this;
    status = processEvents(context, &tv);
    polling = nullptr;
    target = nullptr;
    colourTarget = nullptr;
    return gotFrame;
  }

  int (*init)(freenect_context**, freenect_usb_context*) = nullptr;
  int (*shutdown)(freenect_context*) = nullptr;
  void (*setLogLevel)(freenect_context*, freenect_loglevel) = nullptr;
  void (*selectSubdevices)(freenect_context*, freenect_device_flags) = nullptr;
  int (*numDevices)(freenect_context*) = nullptr;
  int (*openDevice)(freenect_context*, freenect_device**, int) = nullptr;
  int (*closeDevice)(freenect_device*) = nullptr;
  freenect_frame_mode (*findDepthMode)(freenect_resolution, freenect_depth_format) = nullptr;
  int (*setDepthMode)(freenect_device*, freenect_frame_mode) = nullptr;
  void (*setDepthCallback)(freenect_device*, freenect_depth_cb) = nullptr;
  int (*startDepth)(freenect_device*) = nullptr;
  int (*stopDepth)(freenect_device*) = nullptr;
  int (*processEvents)(freenect_context*, timeval*) = nullptr;
  int (*updateTiltState)(freenect_device*) = nullptr;
  freenect_raw_tilt_state* (*getTiltState)(freenect_device*) = nullptr;
  void (*getMksAccel)(freenect_raw_tilt_state*, double*, double*, double*) = nullptr;
  void (*setVideoCallback)(freenect_device*, freenect_video_cb) = nullptr;
  freenect_frame_mode (*findVideoMode)(freenect_resolution, freenect_video_format) = nullptr;
  int (*setVideoMode)(freenect_device*, freenect_frame_mode) = nullptr;
  int (*startVideo)(freenect_device*) = nullptr;
  int (*stopVideo)(freenect_device*) = nullptr;
  freenect_registration (*copyRegistration)(freenect_device*) = nullptr;
  int (*destroyRegistration)(freenect_registration*) = nullptr;

  freenect_context* context = nullptr;
  freenect_device* device = nullptr;
  bool depthStarted = false;
  bool videoStarted = false;
  bool hasAccelerometer = false;  // the motor subdevice is open (live) or the recording may carry 'a' entries

 private:
  // libfreenect started with these subdevices and the first device opened; false when it could not be.
  bool open(const std::string& what, freenect_device_flags subdevices) {
    if (init(&context, nullptr) < 0) {
      context = nullptr;
      throw HandSourceError("no Kinect found: libfreenect could not start (" + what + ", no USB access?)");
    }
    setLogLevel(context, FREENECT_LOG_FATAL);  // a missing motor is handled here, not printed
    selectSubdevices(context, subdevices);
    if (numDevices(context) < 1)
      throw HandSourceError("no Kinect found (" + what + "): is a Kinect v1 plugged in and powered?");
    if (openDevice(context, &device, 0) < 0) {
      device = nullptr;
      return false;
    }
    setLogLevel(context, FREENECT_LOG_ERROR);
    return true;
  }
  void close() {
    if (device) closeDevice(device);
    if (context) shutdown(context);
    device = nullptr;
    context = nullptr;
  }

  template <typename F>
  void bind(F& f, const char* name) {
    f = reinterpret_cast<F>(dlsym(handle_, name));
    if (!f) {
      dlclose(handle_);
      throw HandSourceError(std::string("libfreenect has no ") + name + ": not a libfreenect 0.5 build?");
    }
  }
  template <typename F>
  void bindIfThere(F& f, const char* name) {
    f = reinterpret_cast<F>(dlsym(handle_, name));
  }
  void* handle_ = nullptr;
  kinect::DepthFrame* target = nullptr;
  std::vector<uint8_t>* colourTarget = nullptr;
  bool gotFrame = false;
};

thread_local FreenectLibrary* FreenectLibrary::polling = nullptr;

namespace {
std::atomic<bool> gPlaybackOpen{false};  // fakenect's globals allow one recording at a time
}

DepthStream::DepthStream() : openedAt_(steadySeconds()) {}

DepthStream::~DepthStream() {
  lib_.reset();
  if (recording_) gPlaybackOpen = false;
}

std::unique_ptr<DepthStream> DepthStream::openKinect() {
  const char* path = std::getenv("GIANTBUBBLE_FREENECT_LIBRARY");
  std::unique_ptr<DepthStream> s(new DepthStream());
  s->lib_ = std::make_unique<FreenectLibrary>(path ? path : GB_FREENECT_LIBRARY);
  s->lib_->start("live Kinect");
  // The device's own registration where the library gives it (kept in a recording as device.json); a device whose
  // values are not a Kinect's is registered by the factory constants.
  ColourRegistration registration = factoryRegistration();
  if (const std::string json = s->lib_->deviceJson(); !json.empty()) {
    try {
      registration = registrationFromDeviceJson(json, "the Kinect's registration");
    } catch (const HandSourceError& e) {
      std::fprintf(stderr, "note: %s; the colour is registered by the factory constants\n", e.what());
    }
  }
  s->registration_ = std::make_shared<const ColourRegistration>(registration);
  s->openedAt_ = steadySeconds();
  return s;
}

std::unique_ptr<DepthStream> DepthStream::openRecording(const fs::path& folder) {
  auto index = std::make_unique<FakenectIndex>(readFakenectIndex(folder));
  index->folder = fs::absolute(folder);
  auto registration = std::make_shared<const ColourRegistration>(recordingRegistration(folder));
  if (gPlaybackOpen.exchange(true))
    throw HandSourceError("fakenect recording " + folder.string() +
                          ": another recording is already playing (one at a time)");
  std::unique_ptr<DepthStream> s(new DepthStream());
  s->recording_ = std::move(index);  // from here the destructor releases gPlaybackOpen
  s->registration_ = std::move(registration);
  for (const FakenectEntry& e : s->recording_->entries) {
    if (e.type == 'd') {
      s->firstDepthTime_ = e.time;
      break;
    }
  }
  // fakenect reads FAKENECT_PATH when it starts playing; it must not be unset while the recording plays.
  setenv("FAKENECT_PATH", s->recording_->folder.c_str(), 1);
  const char* path = std::getenv("GIANTBUBBLE_FAKENECT_LIBRARY");
  s->lib_ = std::make_unique<FreenectLibrary>(path ? path : GB_FAKENECT_LIBRARY);
  s->lib_->start("fakenect playback of " + folder.string());
  return s;
}

std::optional<double> DepthStream::length() const {
  if (!recording_) return std::nullopt;
  double last = firstDepthTime_;
  for (const FakenectEntry& e : recording_->entries)
    if (e.type == 'd') last = e.time;
  return last - firstDepthTime_;
}

double DepthStream::clock() const { return steadySeconds() - openedAt_; }

void DepthStream::release() { lib_.reset(); }

DepthStream::Poll DepthStream::poll(kinect::DepthFrame& frame, double timeout) {
  if (!lib_) throw HandSourceLost("the camera was let go of after it was lost");
  if (recording_) {
    // fakenect consumes one INDEX.txt line per call; stop at the last one rather than let it run off the end.
    while (cursor_ < recording_->entries.size()) {
      const FakenectEntry& e = recording_->entries[cursor_];
      if (const std::string problem = fileProblem(recording_->folder, e); !problem.empty())
        throw HandSourceLost("fakenect recording " + recording_->folder.string() + ": " + problem +
                             " (since it was opened)");
      int status = 0;
      const bool got = lib_->pump(frame, colour_, 0.0, status);
      ++cursor_;
      if (status < 0) throw HandSourceLost("fakenect playback failed at " + printable(e.file, 300));
      if (e.type == 'a') gravityUp_ = lib_->gravityUp();  // fakenect keeps the entry as its tilt state
      if (got) {
        frame.time = e.time - firstDepthTime_;
        frame.gravityUp = gravityUp_;
        attachColour(frame);
        return Poll::Frame;
      }
    }
    return Poll::End;
  }
  const double start = clock();
  while (true) {
    int status = 0;
    const double left = timeout - (clock() - start);
    if (lib_->pump(frame, colour_, std::max(0.0, std::min(left, 0.05)), status)) {
      frame.time = clock();
      readAccelerometer();
      frame.gravityUp = gravityUp_;
      attachColour(frame);
      return Poll::Frame;
    }
    if (status < 0)
      throw HandSourceLost("the Kinect stopped responding (unplugged?): libusb error " + std::to_string(status));
    if (clock() - start >= timeout) return Poll::Nothing;
  }
}

void DepthStream::attachColour(kinect::DepthFrame& frame) const {
  frame.colour = colour_;
  frame.registration = colour_.empty() ? nullptr : registration_;
}

void DepthStream::readAccelerometer() {
  // A control transfer per reading: twice a second is plenty for a camera standing still.
  if (!lib_->hasAccelerometer || clock() - accelReadAt_ < kAccelPeriod) return;
  accelReadAt_ = clock();
  if (lib_->updateTiltState(lib_->device) >= 0) gravityUp_ = lib_->gravityUp();
}

std::string DepthStream::describe() const {
  if (recording_)
    return "fakenect recording " + printablePath(recording_->folder) + " (" + std::to_string(recording_->depthFrames) +
           " depth frames)";
  return "live Kinect v1 (libfreenect, 640x480 11-bit depth)";
}

}  // namespace gb
