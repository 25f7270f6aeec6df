#pragma once
// How a run writes its files so that nothing is lost without a word: a whole file (stats.json, a PLY,
// bench --json) is written beside its name as NAME.partial, flushed, closed, checked and renamed over NAME, so a
// reader sees the old file or the new one, never half of one; a file that grows row by row as the run goes
// (stats.csv, wands.csv) checks every row. Every failure is an OutputError naming the file and the reason
// (errno's words: "No space left on device").
//
// Only a regular file or a new path is ever written: a device, a FIFO or a folder where an output should go is
// refused before anything is written (renamed onto, /dev/null would become a file), and a symbolic link is written
// through to its target (the link stays).

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace gb {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The path to write for `path`: itself, or the target of a symbolic link. Throws OutputError naming the file when it
// is something other than a regular file or a new path ("will not write /dev/full: it is a character device").
std::filesystem::path outputTarget(const std::filesystem::path& path);

// Writes `bytes` to `path` atomically. On failure the .partial is removed and a file already at `path` is kept.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

// A file written a row at a time: each row goes to the kernel at once (a run killed hard keeps every row written
// before), and a row that cannot be written whole throws instead of leaving a cut row behind a run that goes on.
class RowFile {
 public:
  explicit RowFile(const std::filesystem::path& path);  // created, or emptied (a regular file only)
  ~RowFile();
  RowFile(const RowFile&) = delete;  // owns the descriptor
  RowFile& operator=(const RowFile&) = delete;
  void write(std::string_view row);
  void close();  // checked; the destructor closes unchecked
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

// The folder a run writes into (--out), created when missing and held while the run lives: a second run into the
// same folder is refused, naming the first, instead of both writing rows into one stats.csv. The hold is flock(2) on
// FOLDER/giantbubble.lock, which the kernel lets go of when the process ends however it ends (a crash, a kill); the
// file keeps the process id and command line of the run that holds it, for the second run's message.
class OutputFolder {
 public:
  // Throws OutputError naming the problem: an empty name, a path that is a file or a device, a folder that cannot be
  // created, or one another run holds.
  explicit OutputFolder(const std::filesystem::path& folder);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;  // owns the lock
  OutputFolder& operator=(const OutputFolder&) = delete;
  static constexpr const char* kLockName = "giantbubble.lock";

 private:
  int lock_ = -1;
};

// Writes all of `bytes` to `fd`, through partial writes and EINTR; false with errno set when it cannot.
bool writeAll(int fd, std::string_view bytes);

}  // namespace gb
