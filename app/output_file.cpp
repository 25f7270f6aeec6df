#include "output_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

#include "untrusted.h"

namespace gb {

namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int error) {
  throw OutputError(what + " " + path.string() + ": " + std::strerror(error));
}

// Opens `path` for writing with `flags` besides O_WRONLY | O_CREAT; a failure names `named` (the file the user
// asked for, not its .partial).
int openForWriting(const std::filesystem::path& path, const std::filesystem::path& named, int flags) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | flags, 0644);
  if (fd < 0) fail("cannot write", named, errno);
  return fd;
}

// "process 1234: giantbubble run --out o/same", for the lock file: who holds the folder.
std::string thisProcess() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string arguments((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!arguments.empty() && arguments.back() == '\0') arguments.pop_back();
  std::replace(arguments.begin(), arguments.end(), '\0', ' ');
  return "process " + std::to_string(::getpid()) + ": " + arguments;
}

// What the lock file says about the run that holds it (its first line).
std::string lockHolder(int fd) {
  char text[512];
  const ssize_t n = ::pread(fd, text, sizeof text, 0);
  const std::string holder(text, static_cast<size_t>(std::max<ssize_t>(n, 0)));
  return holder.substr(0, holder.find('\n'));
}

}  // namespace

std::filesystem::path outputTarget(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path target = path;
  if (fs::is_symlink(fs::symlink_status(path, ec))) {
    target = fs::weakly_canonical(path, ec);
    if (ec) throw OutputError("cannot write " + path.string() + ": " + ec.message());
  }
  const fs::file_type type = fs::status(target, ec).type();
  if (type == fs::file_type::not_found || type == fs::file_type::regular) return target;
  if (ec) throw OutputError("cannot write " + path.string() + ": " + ec.message());
  throw OutputError("will not write " + path.string() + ": it is " + fileKindInWords(type) +
                    " (an output is written to a new path or over a regular file only)");
}

bool writeAll(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return false;
    }
    bytes.remove_prefix(static_cast<size_t>(n));
  }
  return true;
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
  const std::filesystem::path target = outputTarget(path);
  const std::filesystem::path partial = target.string() + ".partial";
  ::unlink(partial.c_str());  // one left by a run that was killed: created anew, so never a FIFO that blocks
  const int fd = openForWriting(partial, path, O_EXCL | O_NOFOLLOW);
  // No fsync: the guard is against a full disk, a signal or a crash of this process, not a power cut, and a
  // flush to the platter for every mesh would slow a run down on a slow disk.
  const bool written = writeAll(fd, bytes);
  const int writeError = errno;
  const bool closed = ::close(fd) == 0;
  const int closeError = errno;
  if (!written || !closed) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    fail("failed writing", path, written ? closeError : writeError);
  }
  std::error_code ec;
  std::filesystem::rename(partial, target, ec);
  if (ec) {
    const std::string why = ec.message();
    std::filesystem::remove(partial, ec);
    throw OutputError("failed writing " + path.string() + ": cannot rename " + partial.string() + ": " + why);
  }
}

RowFile::RowFile(const std::filesystem::path& path)
    : path_(path), fd_(openForWriting(outputTarget(path), path, O_TRUNC)) {}

RowFile::~RowFile() {
  if (fd_ >= 0) ::close(fd_);
}

void RowFile::write(std::string_view row) {
  if (fd_ < 0) throw std::logic_error("RowFile::write after close: " + path_.string());
  if (!writeAll(fd_, row)) fail("failed writing", path_, errno);
}

OutputFolder::OutputFolder(const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  if (folder.empty()) throw OutputError("the output folder's name is empty (--out): give a folder");
  std::error_code ec;
  const fs::file_type type = fs::status(folder, ec).type();
  if (type != fs::file_type::not_found && type != fs::file_type::directory)
    throw OutputError("the output folder " + folder.string() + " is " + fileKindInWords(type) +
                      " (--out): give a folder");
  fs::create_directories(folder, ec);
  if (ec) throw OutputError("cannot create the output folder " + folder.string() + ": " + ec.message());
  const fs::path lockFile = folder / kLockName;
  lock_ = ::open(lockFile.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (lock_ < 0) fail("cannot write", lockFile, errno);
  if (::flock(lock_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string holder = lockHolder(lock_);
    ::close(std::exchange(lock_, -1));
    if (error != EWOULDBLOCK) fail("cannot lock", lockFile, error);
    throw OutputError("another run is writing into " + folder.string() + " (" +
                      printable(holder.empty() ? "its process is starting" : holder, 300) +
                      "): give another --out, or wait until it ends");
  }
  if (::ftruncate(lock_, 0) != 0 || !writeAll(lock_, thisProcess() + "\n")) {
    const int error = errno;
    ::close(std::exchange(lock_, -1));
    fail("failed writing", lockFile, error);
  }
}

OutputFolder::~OutputFolder() {
  if (lock_ >= 0) ::close(lock_);  // lets go of the lock; the file stays (removing it would race a run opening it)
}

void RowFile::close() {
  if (fd_ < 0) return;
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0) fail("failed writing", path_, errno);
}

}  // namespace gb
