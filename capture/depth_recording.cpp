#include "capture/depth_recording.h"

#include <archive.h>
#include <archive_entry.h>
#include <libfreenect.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <random>

#include "capture/colour_registration.h"
#include "capture/freenect_stream.h"
#include "capture/trajectory_file.h"
#include "capture/untrusted.h"

namespace gb {

namespace fs = std::filesystem;

namespace {

// An archive larger than this unpacked is not a recording (a minute of depth is 1.1 GB).
constexpr la_int64_t kMaxUnpackedBytes = la_int64_t{4} << 30;

kinect::DepthFrame readDepthFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string header;
  std::getline(in, header);  // checked by readFakenectIndex
  std::vector<unsigned char> bytes(static_cast<size_t>(kinect::kPixels) * 2);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!in) throw HandSourceError("depth file " + printablePath(file) + " could not be read whole");
  kinect::DepthFrame frame;
  for (size_t i = 0; i < frame.raw.size(); ++i)  // little-endian, as libfreenect hands them out
    frame.raw[i] = static_cast<uint16_t>(bytes[2 * i] | (bytes[2 * i + 1] << 8));
  return frame;
}

// A colour entry's RGB (readFakenectIndex checked its header and size).
std::vector<uint8_t> readColourFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string header;
  std::getline(in, header);
  std::vector<uint8_t> rgb(static_cast<size_t>(kinect::kColourBytes));
  in.read(reinterpret_cast<char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
  if (!in) throw HandSourceError("colour file " + printablePath(file) + " could not be read whole");
  return rgb;
}

// The up direction of an accelerometer entry (libfreenect's freenect_raw_tilt_state as fakenect-record dumps it).
std::optional<Vec3d> readAccelerometer(const fs::path& file) {
  freenect_raw_tilt_state state{};
  std::ifstream in(file, std::ios::binary);
  in.read(reinterpret_cast<char*>(&state), sizeof state);
  if (!in) return std::nullopt;
  const double perCount = kinect::kStandardGravity / kinect::kAccelCountsPerG;
  return kinect::accelToCameraUp(perCount * state.accelerometer_x, perCount * state.accelerometer_y,
                                 perCount * state.accelerometer_z);
}

DepthRecording readFolder(const fs::path& folder, const std::string& name) {
  const FakenectIndex index = readFakenectIndex(folder);
  DepthRecording recording;
  recording.name = name;
  std::optional<Vec3d> gravityUp;
  std::vector<uint8_t> colour;  // the newest colour image
  std::shared_ptr<const ColourRegistration> registration;
  double firstTime = 0.0;
  for (const FakenectEntry& e : index.entries) {
    if (e.type == 'a') gravityUp = readAccelerometer(folder / e.file);
    if (e.type == 'r') {
      colour = readColourFile(folder / e.file);
      if (!registration) registration = std::make_shared<const ColourRegistration>(recordingRegistration(folder));
    }
    if (e.type != 'd') continue;
    kinect::DepthFrame frame = readDepthFile(folder / e.file);
    if (recording.frames.empty()) firstTime = e.time;
    frame.time = e.time - firstTime;
    frame.timestamp = e.timestamp;
    frame.gravityUp = gravityUp;
    frame.colour = colour;
    frame.registration = registration;
    recording.frames.push_back(std::move(frame));
  }
  const fs::path truth = folder / "hands.csv";
  std::error_code ec;
  if (fs::exists(truth, ec)) recording.truth = readTrajectory(truth);
  return recording;
}

// A private folder under the system's temporary folder, removed with this object.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::random_device random;
    path_ = fs::temp_directory_path() / ("giantbubble-recording-" + std::to_string(random()));
    fs::create_directories(path_);
  }
  ~TemporaryFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;  // owns the folder on disk
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// The longest name of an archive's entry unpacked: a recording is a folder of files, and a deeper one would fail
// as the file system's own error.
constexpr size_t kMaxEntryNameBytes = 1024;

// Unpacks the regular files and folders of a .tar.gz under `into`; returns the folder holding INDEX.txt. Any other
// entry (a link, a device) is refused by name: the file a recording reads would be missing without a word.
fs::path unpackArchive(const fs::path& archivePath, const fs::path& into) {
  const std::string where = "recording archive " + printablePath(archivePath);
  std::unique_ptr<archive, decltype(&archive_read_free)> reader(archive_read_new(), archive_read_free);
  archive_read_support_filter_gzip(reader.get());
  archive_read_support_format_tar(reader.get());
  if (archive_read_open_filename(reader.get(), archivePath.c_str(), 1 << 16) != ARCHIVE_OK)
    throw HandSourceError(where + ": " + archive_error_string(reader.get()));
  std::optional<fs::path> recording;
  la_int64_t unpacked = 0;
  archive_entry* entry = nullptr;
  int status = ARCHIVE_OK;
  while ((status = archive_read_next_header(reader.get(), &entry)) == ARCHIVE_OK) {
    const std::string name = archive_entry_pathname(entry) ? archive_entry_pathname(entry) : "";
    const std::string entryName = "the entry '" + printable(name) + "'";
    if (name.size() > kMaxEntryNameBytes)
      throw HandSourceError(where + ": " + entryName + " has a name of " + std::to_string(name.size()) +
                            " bytes, more than " + std::to_string(kMaxEntryNameBytes) + " (not a recording)");
    const fs::path relative = fs::path(name).lexically_normal();
    if (relative.is_absolute() || relative.empty() || *relative.begin() == "..")
      throw HandSourceError(where + ": " + entryName + " points outside the archive");
    const fs::path target = into / relative;
    std::error_code ec;
    if (archive_entry_filetype(entry) == AE_IFDIR) {
      fs::create_directories(target, ec);
      if (ec) throw HandSourceError(where + ": cannot unpack " + entryName + ": " + ec.message());
      continue;
    }
    if (archive_entry_filetype(entry) != AE_IFREG)
      throw HandSourceError(where + ": " + entryName + " is not a regular file (a link or a device; a recording " +
                            "holds files and folders only)");
    unpacked += archive_entry_size(entry);
    if (unpacked > kMaxUnpackedBytes)
      throw HandSourceError(where + ": more than " + std::to_string(kMaxUnpackedBytes >> 30) +
                            " GiB unpacked (not a recording)");
    fs::create_directories(target.parent_path(), ec);
    if (ec) throw HandSourceError(where + ": cannot unpack " + entryName + ": " + ec.message());
    std::ofstream out(target, std::ios::binary);
    const void* block = nullptr;
    size_t size = 0;
    la_int64_t offset = 0;
    int read = ARCHIVE_OK;
    while ((read = archive_read_data_block(reader.get(), &block, &size, &offset)) == ARCHIVE_OK)
      out.write(static_cast<const char*>(block), static_cast<std::streamsize>(size));
    if (read != ARCHIVE_EOF) throw HandSourceError(where + ": " + archive_error_string(reader.get()));
    if (!out) throw HandSourceError(where + ": cannot unpack " + entryName + " into " + printablePath(into));
    if (relative.filename() == "INDEX.txt") recording = target.parent_path();
  }
  if (status != ARCHIVE_EOF) throw HandSourceError(where + ": " + archive_error_string(reader.get()));
  if (!recording) throw HandSourceError(where + ": no INDEX.txt inside (not a fakenect recording)");
  return *recording;
}

std::string recordingName(const fs::path& path) {
  std::string name = path.filename().string();
  if (name.empty()) name = path.parent_path().filename().string();
  for (const char* suffix : {".tar.gz", ".tgz"})
    if (name.size() > std::string(suffix).size() && name.ends_with(suffix))
      return name.substr(0, name.size() - std::string(suffix).size());
  return name;
}

}  // namespace

bool isRecordingArchive(const fs::path& path) {
  const std::string name = path.filename().string();
  return name.ends_with(".tar.gz") || name.ends_with(".tgz");
}

DepthRecording readDepthRecording(const fs::path& path) {
  if (!isRecordingArchive(path)) return readFolder(path, recordingName(path));
  if (const std::string why = whyNotARegularFile(path); !why.empty())
    throw HandSourceError("recording archive " + printablePath(path) + " " + why);
  const TemporaryFolder unpacked;
  return readFolder(unpackArchive(path, unpacked.path()), recordingName(path));
}

}  // namespace gb
