#include "capture/untrusted.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace gb {

namespace {

bool isContinuation(std::string_view text, std::size_t i) {
  return i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80;
}

// The length of the UTF-8 sequence at text[i] (1 for ASCII), or 0 when the bytes there are not UTF-8: a stray
// continuation byte, an overlong form, a surrogate or a sequence cut short.
std::size_t utf8Length(std::string_view text, std::size_t i) {
  const auto lead = static_cast<unsigned char>(text[i]);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  if (lead >= 0xC2 && lead <= 0xDF) length = 2;
  if (lead >= 0xE0 && lead <= 0xEF) length = 3;
  if (lead >= 0xF0 && lead <= 0xF4) length = 4;
  if (length == 0) return 0;
  for (std::size_t k = 1; k < length; ++k)
    if (!isContinuation(text, i + k)) return 0;
  const auto second = static_cast<unsigned char>(text[i + 1]);
  if ((lead == 0xE0 && second < 0xA0) || (lead == 0xED && second > 0x9F) || (lead == 0xF0 && second < 0x90) ||
      (lead == 0xF4 && second > 0x8F))
    return 0;
  return length;
}

// U+0080 to U+009F: control characters too (0x9B is the one-byte CSI some terminals obey).
bool isC1Control(std::string_view text, std::size_t i) {
  return static_cast<unsigned char>(text[i]) == 0xC2 && static_cast<unsigned char>(text[i + 1]) <= 0x9F;
}

// U+061C, U+200E, U+200F, U+202A to U+202E and U+2066 to U+2069: the marks, embeddings, overrides and isolates
// that change the direction text is shown in. The code point, or 0 when the bytes at text[i] are none of them.
unsigned directionControl(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[i + k]); };
  if (byte(0) == 0xD8 && byte(1) == 0x9C) return 0x061C;
  if (byte(0) != 0xE2 || i + 2 >= text.size()) return 0;
  const unsigned code = 0x2000u + ((byte(1) & 0x3Fu) << 6) + (byte(2) & 0x3Fu);
  const bool control =
      code == 0x200E || code == 0x200F || (code >= 0x202A && code <= 0x202E) || (code >= 0x2066 && code <= 0x2069);
  return control ? code : 0;
}

std::string escaped(unsigned char c) {
  switch (c) {
    case '\n':
      return "\\n";
    case '\r':
      return "\\r";
    case '\t':
      return "\\t";
    case '\0':
      return "\\0";
    default: {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      return hex;
    }
  }
}

}  // namespace

std::string fileKindInWords(std::filesystem::file_type type) {
  using std::filesystem::file_type;
  switch (type) {
    case file_type::regular:
      return "a regular file";
    case file_type::directory:
      return "a folder";
    case file_type::character:
      return "a character device";
    case file_type::block:
      return "a block device";
    case file_type::fifo:
      return "a FIFO";
    case file_type::socket:
      return "a socket";
    case file_type::symlink:
      return "a symbolic link";
    default:
      return "neither a file nor a folder";
  }
}

std::string whyNotARegularFile(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) return "does not exist";
  if (ec) return "cannot be read: " + ec.message();  // a loop of symbolic links, a folder without permission
  if (status.type() == std::filesystem::file_type::regular) return {};
  return "is " + fileKindInWords(status.type());
}

std::string printable(std::string_view text, std::size_t maxBytes) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size() && i < maxBytes) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t length = utf8Length(text, i);
    if (length == 1 && c >= 0x20 && c != 0x7F) {
      out += text[i++];
    } else if (const unsigned code = length > 1 ? directionControl(text, i) : 0) {
      char u[12];
      std::snprintf(u, sizeof u, "\\u%04x", code);
      out += u;
      i += length;
    } else if (length > 1 && !isC1Control(text, i)) {
      out.append(text.substr(i, length));
      i += length;
    } else {
      out += escaped(c);
      ++i;
    }
  }
  if (i < text.size()) out += "...(" + std::to_string(text.size()) + " bytes)";
  return out;
}

std::string printablePath(const std::filesystem::path& path) { return printable(path.string(), 300); }

std::string printableNumber(std::string_view text) { return printable(text, 24); }

namespace {

// "20.0 MiB" and the like, for messages about sizes.
std::string inMiB(std::uintmax_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1 << 20));
  return text;
}

}  // namespace

InputFile openInputFile(const std::filesystem::path& path, std::uintmax_t maxBytes, std::string& why) {
  InputFile none(nullptr, std::fclose);
  // O_NONBLOCK: opening a FIFO with no writer would wait for one (and a Ctrl-C would not end the wait: signals
  // restart the open). The kind is then checked on what was opened, not on a name that could change meanwhile.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    const int error = errno;
    why = whyNotARegularFile(path);
    if (why.empty() || error == EACCES) why = std::string("cannot be read: ") + std::strerror(error);
    return none;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    why = S_ISDIR(st.st_mode)    ? "is a folder"
          : S_ISFIFO(st.st_mode) ? "is a FIFO"
          : S_ISCHR(st.st_mode)  ? "is a character device"
          : S_ISBLK(st.st_mode)  ? "is a block device"
          : S_ISSOCK(st.st_mode) ? "is a socket"
                                 : "is not a regular file";
    ::close(fd);
    return none;
  }
  if (static_cast<std::uintmax_t>(st.st_size) > maxBytes) {
    why = "is " + inMiB(static_cast<std::uintmax_t>(st.st_size)) + ", more than the " + inMiB(maxBytes) +
          " such a file may have";
    ::close(fd);
    return none;
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  std::FILE* file = ::fdopen(fd, "rb");
  if (!file) {
    why = std::string("cannot be read: ") + std::strerror(errno);
    ::close(fd);
    return none;
  }
  return {file, std::fclose};
}

bool readWhole(std::FILE* file, std::string& text, std::string& why) {
  text.clear();
  char block[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(block, 1, sizeof block, file)) > 0) text.append(block, n);
  if (!std::ferror(file)) return true;
  why = std::string("cannot be read: ") + std::strerror(errno);
  return false;
}

LineRead readLine(std::FILE* file, std::string& line, std::size_t maxBytes) {
  line.clear();
  int c = 0;
  while ((c = getc_unlocked(file)) != EOF && c != '\n') {
    if (line.size() == maxBytes) {
      while ((c = getc_unlocked(file)) != EOF && c != '\n') {
      }
      return LineRead::TooLong;
    }
    line += static_cast<char>(c);
  }
  return c == EOF && line.empty() ? LineRead::End : LineRead::Line;
}

}  // namespace gb
