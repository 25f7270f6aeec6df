#pragma once
// The real-depth set (../shared/real-depth/utd-mhad, Kinect v1 recordings with ground-truth hands) for the tests that
// judge on it: a recording by name, or a loud skip outside CI and a failure under it when the set is missing.

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "capture/depth_recording.h"
#include "tests/vulkan_test_device.h"

namespace gb {

#ifndef GB_REAL_DEPTH_DIR
#define GB_REAL_DEPTH_DIR "../shared/real-depth/utd-mhad"
#endif

// A recording of the real-data set, or nothing (the test then skips, loudly, outside CI and fails under it).
inline std::optional<DepthRecording> realRecording(const std::string& name) {
  const std::filesystem::path archive = std::filesystem::path(GB_REAL_DEPTH_DIR) / (name + ".tar.gz");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(archive, ec)) return std::nullopt;
  return readDepthRecording(archive);
}

#define REQUIRE_REAL_DEPTH(recording, name)                                                                           \
  const std::optional<DepthRecording> recording = realRecording(name);                                                \
  if (!recording) {                                                                                                   \
    if (test::underCi()) FAIL() << "the real-depth set is missing: " << GB_REAL_DEPTH_DIR << "/" << name;             \
    std::fprintf(stderr, "\n*** SKIPPED: no real-depth set at %s (../shared/real-depth) ***\n\n", GB_REAL_DEPTH_DIR); \
    GTEST_SKIP() << "no real-depth set at " << GB_REAL_DEPTH_DIR;                                                     \
  }

}  // namespace gb
