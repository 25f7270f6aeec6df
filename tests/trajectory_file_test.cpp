#include "capture/trajectory_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace gb {
namespace {

namespace fs = std::filesystem;

fs::path scratchFile(const std::string& name, const std::string& contents) {
  const fs::path path =
      fs::temp_directory_path() / ("giantbubble_trajectory_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << contents;
  return path;
}

std::string errorOf(const fs::path& path) {
  try {
    readTrajectory(path);
  } catch (const HandSourceError& e) {
    fs::remove(path);
    return e.what();
  }
  fs::remove(path);
  return "(no error)";
}

TEST(TrajectoryFile, WritesAndReadsBackWithMissingHandsHeld) {
  const fs::path path = fs::temp_directory_path() / ("giantbubble_trajectory_" + std::to_string(::getpid()) + ".csv");
  std::vector<HandSample> written(3);
  for (int i = 0; i < 3; ++i) {
    written[i].time = 0.5 + i / 30.0;
    written[i].left.position = Vec3d(0.1 * i, 0.2, 1.9);
    written[i].left.measured = true;
    written[i].right.position = Vec3d(-0.3, 0.1, 2.0 - 0.01 * i);
    written[i].right.measured = i != 1;  // missing in the middle row
  }
  {
    TrajectoryWriter writer(path);
    for (const HandSample& s : written) writer.write(s);
    writer.close();
  }
  const std::vector<HandSample> read = readTrajectory(path, 0.5);
  fs::remove(path);
  ASSERT_EQ(read.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(read[i].time, written[i].time, 1e-6);
    EXPECT_LT((read[i].left.position - written[i].left.position).norm(), 1e-6);
    EXPECT_EQ(read[i].right.measured, written[i].right.measured);
  }
  // The missing hand is held at its last position with a decayed confidence.
  EXPECT_EQ(read[1].right.position, read[0].right.position);
  EXPECT_NEAR(read[1].right.confidence, std::exp(-(1 / 30.0) / 0.5), 1e-5);
}

TEST(TrajectoryFile, EveryMalformedFileIsAClearErrorWithItsLine) {
  const std::string header = "t,left_x,left_y,left_z,right_x,right_y,right_z\n";
  EXPECT_NE(errorOf("/nonexistent/hands.csv").find("does not exist"), std::string::npos);
  EXPECT_NE(errorOf(scratchFile("empty", "")).find("empty"), std::string::npos);
  EXPECT_NE(errorOf(scratchFile("header_only", "# comment\n" + header)).find("no samples"), std::string::npos);
  EXPECT_NE(
      errorOf(scratchFile("bad_header", "time,lx,ly,lz,rx,ry,rz\n0,0,0,0,0,0,0\n")).find("line 1: expected the header"),
      std::string::npos);
  EXPECT_NE(errorOf(scratchFile("short", header + "0,1,2,3,4,5,6\n0.1,1,2,3\n")).find("line 3: 4 fields"),
            std::string::npos);
  EXPECT_NE(errorOf(scratchFile("word", header + "0,1,2,x3,4,5,6\n")).find("line 2: left_z 'x3' is not a number"),
            std::string::npos);
  EXPECT_NE(errorOf(scratchFile("partial", header + "0,1,,3,4,5,6\n")).find("left hand has 2 of 3"), std::string::npos);
  EXPECT_NE(errorOf(scratchFile("backwards", header + "0.2,1,2,3,4,5,6\n0.1,1,2,3,4,5,6\n"))
                .find("line 3: time 0.1 s is not after"),
            std::string::npos);
  EXPECT_NE(errorOf(scratchFile("infinite", header + "0,inf,2,3,4,5,6\n")).find("is not a number"), std::string::npos);
  // Comments, blank lines, spaces and a missing hand are fine.
  const fs::path good =
      scratchFile("good", "# from somewhere\n\n" + header + " 0.0 , 1, 2, 3 ,,, \n0.1,1,2,3,4,5,6\r\n");
  const auto samples = readTrajectory(good);
  fs::remove(good);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_FALSE(samples[0].right.seen());
  EXPECT_TRUE(samples[1].right.measured);
}

}  // namespace
}  // namespace gb
