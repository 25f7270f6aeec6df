#include "output_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace gb {

namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int error) {
  throw OutputError(what + " " + path.string() + ": " + std::strerror(error));
}

// Opens `path` for writing; a failure names `named` (the file the user asked for, not its .partial).
int openForWriting(const std::filesystem::path& path, const std::filesystem::path& named) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot write", named, errno);
  return fd;
}

}  // namespace

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
  const std::filesystem::path partial = path.string() + ".partial";
  const int fd = openForWriting(partial, path);
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
  std::filesystem::rename(partial, path, ec);
  if (ec) {
    std::filesystem::remove(partial, ec);
    throw OutputError("failed writing " + path.string() + ": cannot rename " + partial.string() + ": " + ec.message());
  }
}

RowFile::RowFile(const std::filesystem::path& path) : path_(path), fd_(openForWriting(path, path)) {}

RowFile::~RowFile() {
  if (fd_ >= 0) ::close(fd_);
}

void RowFile::write(std::string_view row) {
  if (fd_ < 0) throw std::logic_error("RowFile::write after close: " + path_.string());
  if (!writeAll(fd_, row)) fail("failed writing", path_, errno);
}

void RowFile::close() {
  if (fd_ < 0) return;
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0) fail("failed writing", path_, errno);
}

}  // namespace gb
