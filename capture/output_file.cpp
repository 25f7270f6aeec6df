#include "capture/output_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

#include "capture/untrusted.h"

namespace gb {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& what, const fs::path& path, int error) {
  throw OutputError(what + " " + printablePath(path) + ": " + std::strerror(error));
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

// Takes the hold of a lock file, or says who has it.
void lockOrName(int fd, const fs::path& lockFile, const fs::path& folder) {
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return;
  const int error = errno;
  const std::string holder = lockHolder(fd);
  ::close(fd);
  if (error != EWOULDBLOCK) fail("cannot lock", lockFile, error);
  throw OutputError("another run is writing into " + printablePath(folder) + " (" +
                    printable(holder.empty() ? "its process is starting" : holder, 300) +
                    "): give another output, or wait until it ends");
}

// Checks the NAME.partial beside an output: none, or one a killed process left behind, which `remove` removes. One
// that is no regular file (a FIFO is not ours to delete) or that another process holds while writing it is refused.
void checkPartial(const fs::path& partial, const fs::path& named, bool remove) {
  struct stat st {};
  if (::lstat(partial.c_str(), &st) != 0) return;  // none
  if (!S_ISREG(st.st_mode)) {
    const fs::file_type type = fs::symlink_status(partial).type();
    throw OutputError("will not write " + printablePath(named) + ": " + printablePath(partial) + " is " +
                      fileKindInWords(type) + ", not a file left by an earlier write: remove it, or give another name");
  }
  const int fd = ::open(partial.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
    ::close(fd);
    throw OutputError("another process is writing " + printablePath(named) + " (it holds " + printablePath(partial) +
                      "): give another name, or wait until it ends");
  }
  if (remove) ::unlink(partial.c_str());
  if (fd >= 0) ::close(fd);
}

// `path` with its symbolic links followed, also to a target that does not exist yet (written through, the link
// stays); throws OutputError on a loop.
fs::path followLinks(const fs::path& path) {
  fs::path p = path;
  for (int depth = 0; depth < 40; ++depth) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(p, ec))) return p;
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) throw OutputError("cannot write " + printablePath(path) + ": " + ec.message());
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  fail("cannot write", path, ELOOP);
}

// The nearest folder at or above `path` that exists (itself when it does).
fs::path existingAncestor(const fs::path& path) {
  fs::path p = path.empty() ? fs::path(".") : path;
  std::error_code ec;
  while (!fs::exists(p, ec) && p.has_relative_path() && p != p.parent_path()) p = p.parent_path();
  return p.empty() ? fs::path(".") : p;
}

// The folder an output goes into can be written: it exists (or, with makesFolders, the nearest folder above it
// that does), is a folder and is writable.
void checkWritableFolder(const Output& out) {
  const fs::path parent = out.path.has_parent_path() ? out.path.parent_path() : fs::path(".");
  const fs::path folder = out.makesFolders ? existingAncestor(parent) : parent;
  std::error_code ec;
  const fs::file_type type = fs::status(folder, ec).type();
  if (type == fs::file_type::not_found) fail("cannot write", out.path, ENOENT);
  if (ec) throw OutputError("cannot write " + printablePath(out.path) + ": " + ec.message());
  if (type != fs::file_type::directory)
    throw OutputError("cannot write " + printablePath(out.path) + ": " + printablePath(folder) + " is " +
                      fileKindInWords(type) + ", not a folder");
  if (::access(folder.c_str(), W_OK | X_OK) != 0) fail("cannot write", out.path, errno);
}

// Whether `inner` is `outer` or lies inside it (both canonical).
bool within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

std::string named(const Output& out) { return (out.option.empty() ? "" : out.option + " ") + printablePath(out.path); }

// An output's name: not empty, with its extension.
void checkName(const Output& out) {
  if (out.path.empty())
    throw OutputError(std::string("the name is empty: give a ") + (out.kind == Output::Kind::File ? "file" : "folder"));
  if (out.kind == Output::Kind::File && !out.extension.empty()) {
    std::string extension = out.path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (extension != out.extension)
      throw OutputError(printablePath(out.path) + " does not end in " + out.extension + ", and " + out.extension +
                        " is what is written into it: give a name ending in " + out.extension);
  }
}

// Where an output goes: a kind that can be written, in a writable folder.
void checkPlace(const Output& out) {
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(out.path, ec);
  if (ec && link.type() != fs::file_type::not_found)
    throw OutputError("cannot write " + printablePath(out.path) + ": " + ec.message());  // a name too long
  if (out.kind == Output::Kind::File) {
    checkPartial(outputTarget(out.path).string() + ".partial", out.path, false);
  } else {
    const fs::file_type type = fs::status(out.path, ec).type();
    if (fs::is_symlink(link) && type == fs::file_type::not_found)
      throw OutputError(printablePath(out.path) + " is a symbolic link to " +
                        printablePath(fs::read_symlink(out.path, ec)) + ", which does not exist: give a folder");
    if (type != fs::file_type::not_found && type != fs::file_type::directory)
      throw OutputError(printablePath(out.path) + " is " + fileKindInWords(type) + ": give a folder");
  }
  checkWritableFolder(out);
}

// No two outputs are one file, and none is inside a folder another fills whole.
void checkDistinct(const std::vector<Output>& outputs) {
  std::vector<fs::path> where;
  for (const Output& out : outputs) {
    std::error_code ec;
    const fs::path target = fs::absolute(followLinks(out.path));
    const fs::path canonical = fs::weakly_canonical(target, ec);
    where.push_back(ec ? target.lexically_normal() : canonical);
  }
  for (size_t a = 0; a < outputs.size(); ++a)
    for (size_t b = 0; b < outputs.size(); ++b) {
      if (a == b) continue;
      if (a < b && where[a] == where[b])
        throw OutputError(named(outputs[a]) + " and " + named(outputs[b]) +
                          " are one file: give each output a name of its own");
      if (outputs[b].kind == Output::Kind::NewFolder && within(where[a], where[b]))
        throw OutputError(named(outputs[a]) + " is inside " + named(outputs[b]) +
                          ", which the command fills: give a name outside it");
    }
}

}  // namespace

fs::path outputTarget(const fs::path& path) {
  std::error_code ec;
  const fs::path target = followLinks(path);
  const fs::file_type type = fs::status(target, ec).type();
  if (type == fs::file_type::not_found || type == fs::file_type::regular) return target;
  if (ec) throw OutputError("cannot write " + printablePath(path) + ": " + ec.message());
  throw OutputError("will not write " + printablePath(path) + ": it is " + fileKindInWords(type) +
                    " (an output is written to a new path or over a regular file only)");
}

std::vector<OutputFolder> checkOutputs(const std::vector<Output>& outputs) {
  const auto eachOutput = [&](void (*check)(const Output&)) {
    for (const Output& out : outputs) {
      try {
        check(out);
      } catch (const OutputError& e) {
        throw OutputError(out.option.empty() ? e.what() : out.option + ": " + e.what());
      }
    }
  };
  eachOutput(checkName);
  checkDistinct(outputs);
  eachOutput(checkPlace);
  // The folders to hold: the command's own, then any run folder another output goes into (each once: a second
  // flock of one file from this process would be refused as another run's).
  std::vector<OutputFolder> holds;
  std::vector<fs::path> held;
  const auto canonical = [](const fs::path& folder) {
    std::error_code ec;
    return fs::weakly_canonical(fs::absolute(folder), ec);
  };
  const auto hold = [&](const fs::path& folder, bool own) {
    std::error_code ec;
    if (!own && !fs::exists(folder / OutputFolder::kLockName, ec)) return;
    if (std::find(held.begin(), held.end(), canonical(folder)) != held.end()) return;
    holds.emplace_back(folder);  // an own folder is created here
    held.push_back(canonical(folder));
  };
  for (const Output& out : outputs)
    if (out.kind == Output::Kind::Folder) hold(out.path, true);
  for (const Output& out : outputs)
    if (out.kind != Output::Kind::Folder) hold(out.path.has_parent_path() ? out.path.parent_path() : ".", false);
  return holds;
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

PartialFile::PartialFile(const fs::path& path)
    : named_(path), target_(outputTarget(path)), partial_(target_.string() + ".partial") {
  checkPartial(partial_, named_, true);
  fd_ = ::open(partial_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd_ < 0 && errno == EEXIST)  // made by another process since the stale one was removed
    throw OutputError("another process is writing " + printablePath(named_) + " (it holds " + printablePath(partial_) +
                      "): give another name, or wait until it ends");
  if (fd_ < 0) fail("cannot write", named_, errno);
  ::flock(fd_, LOCK_EX | LOCK_NB);  // a new file: nobody else holds it
}

PartialFile::~PartialFile() {
  if (fd_ < 0) return;
  ::close(fd_);
  ::unlink(partial_.c_str());
}

void PartialFile::commit() {
  if (fd_ < 0) throw std::logic_error("PartialFile::commit twice: " + named_.string());
  // No fsync: the guard is against a full disk, a signal or a crash of this process, not a power cut, and a
  // flush to the platter for every mesh would slow a run down on a slow disk.
  if (::close(std::exchange(fd_, -1)) != 0) {
    const int error = errno;
    ::unlink(partial_.c_str());
    fail("failed writing", named_, error);
  }
  if (::rename(partial_.c_str(), target_.c_str()) != 0) {
    const int error = errno;
    ::unlink(partial_.c_str());
    throw OutputError("failed writing " + printablePath(named_) + ": cannot rename " + printablePath(partial_) + ": " +
                      std::strerror(error));
  }
}

void writeFileAtomically(const fs::path& path, std::string_view bytes) {
  PartialFile file(path);
  if (!writeAll(file.fd(), bytes)) fail("failed writing", path, errno);  // the PartialFile goes, the old file stays
  file.commit();
}

RowFile::RowFile(const fs::path& path, Place place) : path_(path) {
  if (place == Place::AtClose) {
    partial_.emplace(path);
    fd_ = partial_->fd();
    return;
  }
  fd_ = ::open(outputTarget(path).c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | O_TRUNC, 0644);
  if (fd_ < 0) fail("cannot write", path, errno);
}

RowFile::~RowFile() {
  if (!partial_ && fd_ >= 0) ::close(fd_);  // a PartialFile closes and removes its own
}

void RowFile::write(std::string_view row) {
  if (fd_ < 0) throw std::logic_error("RowFile::write after close: " + path_.string());
  if (!writeAll(fd_, row)) fail("failed writing", path_, errno);
}

void RowFile::close() {
  if (fd_ < 0) return;
  const int fd = std::exchange(fd_, -1);
  if (partial_) {
    partial_->commit();
    return;
  }
  if (::close(fd) != 0) fail("failed writing", path_, errno);
}

OutputFolder::OutputFolder(const fs::path& folder) {
  if (folder.empty()) throw OutputError("the output folder's name is empty (--out): give a folder");
  std::error_code ec;
  const fs::file_type type = fs::status(folder, ec).type();
  if (ec && type != fs::file_type::not_found)
    throw OutputError("cannot use the output folder " + printablePath(folder) + ": " + ec.message());
  if (fs::is_symlink(fs::symlink_status(folder, ec)) && type == fs::file_type::not_found)
    throw OutputError("the output folder " + printablePath(folder) + " is a symbolic link to " +
                      printablePath(fs::read_symlink(folder, ec)) + ", which does not exist: give a folder");
  if (type != fs::file_type::not_found && type != fs::file_type::directory)
    throw OutputError("the output folder " + printablePath(folder) + " is " + fileKindInWords(type) +
                      " (--out): give a folder");
  fs::create_directories(folder, ec);
  if (ec) throw OutputError("cannot create the output folder " + printablePath(folder) + ": " + ec.message());
  const fs::path lockFile = folder / kLockName;
  const int fd = ::open(lockFile.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) fail("cannot write", lockFile, errno);
  lockOrName(fd, lockFile, folder);
  lock_ = fd;
  if (::ftruncate(lock_, 0) != 0 || !writeAll(lock_, thisProcess() + "\n")) {
    const int error = errno;
    ::close(std::exchange(lock_, -1));
    fail("failed writing", lockFile, error);
  }
}

OutputFolder::OutputFolder(OutputFolder&& other) noexcept : lock_(std::exchange(other.lock_, -1)) {}

OutputFolder::~OutputFolder() {
  if (lock_ >= 0) ::close(lock_);  // lets go of the lock; the file stays (removing it would race a run opening it)
}

}  // namespace gb
