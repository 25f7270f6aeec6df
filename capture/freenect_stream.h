#pragma once
// Raw 11-bit depth frames through libfreenect, from a live Kinect v1 or from a fakenect recording, by the
// same calls on the same code path. Both are libfreenect builds with the same API: the live library
// (libfreenect.so.0.5) and Debian's fakenect build of it (…/fakenect/libfreenect.so.0.5, which reads the
// folder named by FAKENECT_PATH). We dlopen the one we need (RTLD_LOCAL, so the two never bind to each
// other's symbols) instead of linking either, and the `fakenect` wrapper script is not needed.
//
// Depth is always asked for as FREENECT_DEPTH_11BIT: Debian's fakenect 0.5.3 plays back nothing else.
// Colour is asked for as FREENECT_VIDEO_RGB at 640x480 where the library has the video calls: each depth frame carries
// the newest colour image (and how to register it: a recording's device.json, else the factory constants).
// The camera and the motor subdevices are opened, the motor for its accelerometer only (read twice a second
// live, from the recording's 'a' entries in playback): the tilt is never set and the LED is left alone.
//
// fakenect keeps its playback state in globals and calls exit() on a missing or malformed file, so a
// recording is validated in full before playback starts and each file is checked again just before
// fakenect reads it; one recording plays at a time per process.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "capture/kinect_depth.h"

namespace gb {

// A fakenect recording folder: INDEX.txt lists one file per line, named TYPE-TIME-TIMESTAMP…, where TYPE is
// d (depth, a one-line PGM header then 640x480 little-endian uint16 raw values), r (colour, a one-line PPM header then
// 640x480 RGB) or a (accelerometer),
// TIME the wall-clock seconds when it was recorded and TIMESTAMP the Kinect's frame counter (docs/formats.md).
struct FakenectEntry {
  char type = 'd';
  double time = 0.0;
  uint32_t timestamp = 0;
  std::string file;
};

struct FakenectIndex {
  std::filesystem::path folder;
  std::vector<FakenectEntry> entries;
  int depthFrames = 0;
};

// The longest pause between two entries of a recording (s): fakenect sleeps through each pause as it plays.
inline constexpr double kMaxFakenectGap = 10.0;
// The largest INDEX.txt read (bytes): an hour at 30 frames a second is about 10 MiB of entries.
inline constexpr std::uintmax_t kMaxIndexBytes = std::uintmax_t{64} << 20;
// The longest line of INDEX.txt read (bytes): an entry is a file name of about 30.
inline constexpr std::size_t kMaxIndexLineBytes = 4096;
// The most entries at one time: a depth frame, a colour image and an accelerometer reading. More are a time that
// does not advance (200,000 frames at one time took fakenect minutes before the first frame).
inline constexpr int kMaxEntriesAtOneTime = 3;

// Reads and checks a recording: every listed file present and non-empty, every depth file complete with a
// 'P5 640 480 MAX' header, every colour file complete with a 'P6 640 480 255' header, every accelerometer file a whole
// tilt state, LF line endings, depth frames in time order,
// no pause longer than kMaxFakenectGap and no more than kMaxEntriesAtOneTime entries at one time.
// Throws HandSourceError naming the folder, the line or the file and what is wrong.
FakenectIndex readFakenectIndex(const std::filesystem::path& folder);

// Writes depth frames as a fakenect recording, the way fakenect-record does (raw values in the machine's
// little-endian order after a "P5 640 480 65535" line). Every file is written whole (output_file.h: an OutputError
// naming the file and the reason when it cannot be), INDEX.txt anew after every frame, so a recording that stops
// early is still complete up to its last frame.
class FakenectWriter {
 public:
  explicit FakenectWriter(const std::filesystem::path& folder);  // creates the folder; refuses a non-empty one
  // recordTime: wall-clock seconds of the frame (fakenect replays the differences). A frame that carries the
  // accelerometer's gravity gets an 'a' entry before it, as fakenect-record writes them, and one that carries a colour
  // image an 'r' entry (a "P6 640 480 255" line, then RGB); the first colour image's registration, when it came from a
  // device.json, is written as the recording's device.json.
  void write(const kinect::DepthFrame& frame, double recordTime);
  [[nodiscard]] int frames() const { return frames_; }

 private:
  void writeAccelerometer(const Eigen::Vector3d& up, uint32_t timestamp, double recordTime);
  void writeColour(const kinect::DepthFrame& frame, double recordTime);
  void addToIndex(const std::string& entry);
  std::filesystem::path folder_;
  std::string index_;
  int frames_ = 0;
  bool wroteRegistration_ = false;
};

class FreenectLibrary;

class DepthStream {
 public:
  // The first Kinect on the USB bus. Throws HandSourceError("no Kinect found …") without one.
  static std::unique_ptr<DepthStream> openKinect();
  // A recording, validated first (readFakenectIndex), then played through the fakenect library.
  static std::unique_ptr<DepthStream> openRecording(const std::filesystem::path& folder);
  ~DepthStream();
  DepthStream(const DepthStream&) = delete;  // owns the library handle and libfreenect's device
  DepthStream& operator=(const DepthStream&) = delete;

  enum class Poll { Frame, Nothing, End };
  // Waits up to `timeout` seconds for the next depth frame. Frame: `frame` holds it. Nothing: none came (a live
  // camera only). End: the recording is over. Throws HandSourceLost when libfreenect fails or a recording's
  // file has gone since it was opened.
  Poll poll(kinect::DepthFrame& frame, double timeout);
  [[nodiscard]] std::string describe() const;
  // A recording's length (s, first depth frame to last); nothing for a live camera.
  [[nodiscard]] std::optional<double> length() const;
  // Seconds since the stream opened (live); frame times are on this clock.
  [[nodiscard]] double clock() const;
  // Closes the device and unloads libfreenect now: a lost camera must be let go of before it can be opened
  // again (a device still open in this process cannot be claimed a second time). poll() then throws.
  void release();

 private:
  DepthStream();
  std::unique_ptr<FreenectLibrary> lib_;
  std::unique_ptr<FakenectIndex> recording_;
  size_t cursor_ = 0;  // next INDEX.txt entry fakenect will read
  double firstDepthTime_ = 0.0;
  double openedAt_ = 0.0;                     // steady clock at open (s)
  std::optional<Eigen::Vector3d> gravityUp_;  // the newest accelerometer reading, camera space
  std::vector<uint8_t> colour_;               // the newest colour image (empty: none yet, or no colour stream)
  std::shared_ptr<const ColourRegistration> registration_;  // the recording's device.json or the factory constants
  void attachColour(kinect::DepthFrame& frame) const;
  double accelReadAt_ = -1.0;                  // clock() of the last live reading
  static constexpr double kAccelPeriod = 0.5;  // s between live readings
  void readAccelerometer();                    // live: a new reading when the last is kAccelPeriod old
  friend class FreenectLibrary;
};

}  // namespace gb
