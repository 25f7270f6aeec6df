#pragma once
// How a run writes its files so that nothing is lost without a word (issue 14): a whole file (stats.json, a PLY,
// bench --json) is written beside its name as NAME.partial, flushed, closed, checked and renamed over NAME, so a
// reader sees the old file or the new one, never half of one; a file that grows row by row as the run goes
// (stats.csv, wands.csv) checks every row. Every failure is an OutputError naming the file and the reason
// (errno's words: "No space left on device").

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace gb {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `bytes` to `path` atomically. On failure the .partial is removed and a file already at `path` is kept.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

// A file written a row at a time: each row goes to the kernel at once (a run killed hard keeps every row written
// before), and a row that cannot be written whole throws instead of leaving a cut row behind a run that goes on.
class RowFile {
 public:
  explicit RowFile(const std::filesystem::path& path);  // created, or emptied
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

// Writes all of `bytes` to `fd`, through partial writes and EINTR; false with errno set when it cannot.
bool writeAll(int fd, std::string_view bytes);

}  // namespace gb
