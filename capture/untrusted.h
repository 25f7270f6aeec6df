#pragma once
// Untrusted input on its way into a message: a path the user gave may name a device, a FIFO or a folder instead of
// a file, and text read from a file may hold control characters (a terminal obeys an escape sequence printed raw)
// or run to megabytes. Every message that names such a path or quotes such text goes through these.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace gb {

// What `path` is when it is not a regular file to read, in words ("does not exist", "is a folder", "is a character
// device", "is a FIFO", "cannot be read: Too many levels of symbolic links"); empty when it is a regular file (a
// symbolic link is followed).
std::string whyNotARegularFile(const std::filesystem::path& path);

// The kind of a file in words: "a regular file", "a folder", "a character device", "a FIFO", ...
std::string fileKindInWords(std::filesystem::file_type type);

// `text` as it can be printed: control characters, the controls of the text's direction (a right-to-left override
// would show a message's words in another order) and bytes that are not UTF-8 escaped (\n, \x1b, \0, \u202e), and
// cut after `maxBytes` with the length of the whole ("...(10485760 bytes)").
inline constexpr std::size_t kMaxQuotedBytes = 80;
std::string printable(std::string_view text, std::size_t maxBytes = kMaxQuotedBytes);

// A path as a message names it: printable, cut after 300 bytes.
std::string printablePath(const std::filesystem::path& path);

// A number from untrusted text as a message names it: as it was written, escaped and cut to 24 bytes (a 300-digit
// number is not printed whole, nor 3600.0000001 rounded to 3600).
std::string printableNumber(std::string_view text);

// An input file open for reading.
using InputFile = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

// Opens `path` for reading if it is a regular file of at most `maxBytes`: a FIFO, a device or a folder is named as
// such without waiting on it (opened without blocking, then checked on the open file itself), and a file too large
// before a byte of it is read. Null, with `why` in words ("is a FIFO", "is 20 MiB, more than 1 MiB", "cannot be
// read: Permission denied"), when it is not.
InputFile openInputFile(const std::filesystem::path& path, std::uintmax_t maxBytes, std::string& why);

// The whole of a file opened by openInputFile (its size is bounded there); false with `why` when it cannot be read.
bool readWhole(std::FILE* file, std::string& text, std::string& why);

// Reads one line of `file` (without its '\n') into `line`; a line longer than `maxBytes` is not read whole (the rest
// of it is skipped and TooLong returned), so that one line cannot take the memory a whole file would.
enum class LineRead { Line, End, TooLong };
LineRead readLine(std::FILE* file, std::string& line, std::size_t maxBytes);

}  // namespace gb
