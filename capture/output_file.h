#pragma once
// How every command writes its files, so that nothing is lost or mixed without a word.
//
// Before anything is written, a command checks all its outputs at once (checkOutputs): each is named, ends in the
// extension of what is written into it, is a regular file or a new path in a folder that can be written, is no other
// output of the command (nor inside a folder another output fills), and is in no folder another run holds. Then:
// - a whole file (stats.json, a PLY, a plot, bench --json, the video) is written beside its name as NAME.partial,
//   held (flock) while it is written, and renamed over NAME when complete, so a reader sees the old file or the new
//   one, never half of one; a NAME.partial another process holds is refused, naming it, and one a killed process
//   left behind is replaced;
// - a file that grows row by row as a run goes (stats.csv, wands.csv, in the folder the run holds) is written in
//   place, every row checked, so that a run killed hard keeps every row written before; a recorded trajectory grows
//   in its NAME.partial and is renamed when the recording ends.
// Every failure is an OutputError naming the file, the option that named it where there is one, and the reason
// (errno's words: "No space left on device").
//
// Only a regular file or a new path is ever written: a device, a FIFO or a folder where an output should go is
// refused before anything is written (renamed onto, /dev/null would become a file), and a symbolic link is written
// through to its target (the link stays).

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace gb {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output a command is asked to write, as the user named it.
struct Output {
  enum class Kind {
    File,       // a file
    Folder,     // a folder the command writes its files into (run --out); others may go in it too
    NewFolder,  // a folder the command fills whole (record --fakenect): no other output may be inside it
  };
  std::string option;  // what named it, for messages: "--trajectory"; empty for a file a folder holds
  std::filesystem::path path;
  Kind kind = Kind::File;
  std::string extension;      // a file's: ".csv" (any case); empty: any name
  bool makesFolders = false;  // missing folders above it are created (--out, --video sub/show.mp4)
};

class OutputFolder;

// Checks a command's outputs before any is written, as said above, and holds the folders they go into that are run
// folders (those with a giantbubble.lock, and the command's own Kind::Folder, created here): keep the holds while
// writing. Throws OutputError naming the first problem.
[[nodiscard]] std::vector<OutputFolder> checkOutputs(const std::vector<Output>& outputs);

// The path to write for `path`: itself, or the target of a symbolic link. Throws OutputError naming the file when it
// is something other than a regular file or a new path ("will not write /dev/full: it is a character device").
std::filesystem::path outputTarget(const std::filesystem::path& path);

// NAME.partial beside an output while it is written: created anew and held (flock) until commit() renames it over
// NAME, or removed when it goes uncommitted (an error on the way: the file at NAME is kept as it was). Throws
// OutputError when NAME cannot be written, or when another process holds NAME.partial.
class PartialFile {
 public:
  explicit PartialFile(const std::filesystem::path& path);
  ~PartialFile();
  PartialFile(const PartialFile&) = delete;  // owns the descriptor and the file
  PartialFile& operator=(const PartialFile&) = delete;
  [[nodiscard]] int fd() const { return fd_; }
  [[nodiscard]] const std::filesystem::path& partialPath() const { return partial_; }
  void commit();  // closes (checked) and renames; OutputError naming the file

 private:
  std::filesystem::path named_, target_, partial_;
  int fd_ = -1;
};

// Writes `bytes` to `path` atomically (a PartialFile). On failure a file already at `path` is kept.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

// A file written a row at a time: each row goes to the kernel at once (a run killed hard keeps every row written
// before), and a row that cannot be written whole throws instead of leaving a cut row behind a run that goes on.
class RowFile {
 public:
  enum class Place {
    InPlace,  // created, or emptied (a regular file only): the rows are there as they are written
    AtClose,  // grown in NAME.partial, renamed over NAME by close(): the old file stays until then
  };
  explicit RowFile(const std::filesystem::path& path, Place place = Place::InPlace);
  ~RowFile();
  RowFile(const RowFile&) = delete;  // owns the descriptor
  RowFile& operator=(const RowFile&) = delete;
  void write(std::string_view row);
  void close();  // checked; the destructor closes unchecked (and drops an AtClose file's rows)
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::optional<PartialFile> partial_;
  int fd_ = -1;
};

// The folder a run writes into (--out), created when missing and held while the run lives: a second run into the
// same folder is refused, naming the first, instead of both writing rows into one stats.csv. The hold is flock(2) on
// FOLDER/giantbubble.lock, which the kernel lets go of when the process ends however it ends (a crash, a kill); the
// file keeps the process id and command line of the run that holds it, for the second run's message. Any other
// command writing into a folder that has a giantbubble.lock takes the same hold while it writes (checkOutputs).
class OutputFolder {
 public:
  // Throws OutputError naming the problem: an empty name, a path that is a file or a device, a folder that cannot be
  // created, or one another run holds.
  explicit OutputFolder(const std::filesystem::path& folder);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;  // owns the lock
  OutputFolder& operator=(const OutputFolder&) = delete;
  OutputFolder(OutputFolder&& other) noexcept;
  OutputFolder& operator=(OutputFolder&&) = delete;
  static constexpr const char* kLockName = "giantbubble.lock";

 private:
  int lock_ = -1;
};

// Writes all of `bytes` to `fd`, through partial writes and EINTR; false with errno set when it cannot.
bool writeAll(int fd, std::string_view bytes);

}  // namespace gb
