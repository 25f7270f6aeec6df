#pragma once
// Untrusted input on its way into a message: a path the user gave may name a device, a FIFO or a folder instead of
// a file, and text read from a file may hold control characters (a terminal obeys an escape sequence printed raw)
// or run to megabytes. Every message that names such a path or quotes such text goes through these.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace gb {

// What `path` is when it is not a regular file to read, in words ("does not exist", "is a folder", "is a character
// device", "is a FIFO", "cannot be read: Too many levels of symbolic links"); empty when it is a regular file (a
// symbolic link is followed).
std::string whyNotARegularFile(const std::filesystem::path& path);

// The kind of a file in words: "a regular file", "a folder", "a character device", "a FIFO", ...
std::string fileKindInWords(std::filesystem::file_type type);

// `text` as it can be printed: control characters and bytes that are not UTF-8 escaped (\n, \x1b, \0), and cut after
// `maxBytes` with the length of the whole ("...(10485760 bytes)").
inline constexpr std::size_t kMaxQuotedBytes = 80;
std::string printable(std::string_view text, std::size_t maxBytes = kMaxQuotedBytes);

}  // namespace gb
