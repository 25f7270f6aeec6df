// fakenect recordings: INDEX.txt and the depth frames' headers. The input is INDEX.txt, then a NUL byte, then
// the header line every listed file gets (followed by a full frame of zero depth, as a sparse file), so that
// the fuzzer reaches the frame checks without writing 600 KB per file. Any input is a recording or a
// HandSourceError naming the problem.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "capture/freenect_stream.h"
#include "capture/hand_source.h"
#include "capture/kinect_depth.h"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const fs::path folder =
      fs::temp_directory_path() / ("giantbubble_fuzz_fakenect_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string input(reinterpret_cast<const char*>(data), size);
  const size_t nul = input.find('\0');
  const std::string index = input.substr(0, nul);
  const std::string header = nul == std::string::npos ? "P5 640 480 65535" : input.substr(nul + 1);
  std::ofstream(folder / "INDEX.txt", std::ios::binary) << index;
  std::istringstream lines(index);
  int files = 0;
  for (std::string line; std::getline(lines, line) && files < 8;) {
    // Only plain names inside the folder: the harness must not write elsewhere.
    if (line.empty() || line.size() > 200 || line.find('/') != std::string::npos || line == "." || line == ".." ||
        line.find('\0') != std::string::npos)
      continue;
    {
      std::ofstream frame(folder / line, std::ios::binary);
      frame << header << '\n';
    }
    std::error_code ec;
    fs::resize_file(folder / line, header.size() + 1 + static_cast<size_t>(gb::kinect::kPixels) * 2, ec);
    ++files;
  }
  try {
    (void)gb::readFakenectIndex(folder);
  } catch (const gb::HandSourceError&) {
  }
  return 0;
}
