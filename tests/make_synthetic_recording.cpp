// Writes the synthetic performer session (synthetic_depth.h) as a fakenect recording, for the command-line
// tests: make_synthetic_recording DIR FRAMES [--truncate | --nobody-until SECONDS]. With --truncate the last depth
// file is cut short; with --nobody-until the room is empty until then (a performer who walks in late).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "capture/freenect_stream.h"
#include "tests/synthetic_depth.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s DIR FRAMES [--truncate | --nobody-until SECONDS]\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  const int frames = std::atoi(argv[2]);
  const double nobodyUntil = argc > 4 && std::string(argv[3]) == "--nobody-until" ? std::atof(argv[4]) : 0.0;
  std::filesystem::remove_all(dir);
  gb::FakenectWriter writer(dir);
  for (int i = 0; i < frames; ++i) {
    const double t = i / 30.0;
    // The performer walks in with the hands at the session's start: 0.5 m apart, the rest pose's spacing.
    gb::test::SyntheticPerformer pose = gb::test::sessionPose(std::max(t - nobodyUntil, 0.0));
    pose.present = t >= nobodyUntil;
    writer.write(gb::test::renderPerformer(pose, t, static_cast<uint32_t>(i)), 1000.0 + t);
  }
  if (argc > 3 && std::string(argv[3]) == "--truncate") {
    std::ifstream index(dir / "INDEX.txt");
    std::string line, last;
    while (std::getline(index, line)) last = line;
    std::filesystem::resize_file(dir / last, 4096);
  }
  std::printf("wrote %d frames to %s\n", frames, dir.c_str());
  return 0;
}
