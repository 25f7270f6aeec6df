#include "untrusted.h"

#include <cstdio>

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

}  // namespace gb
