// The run's record (app/outputs/run_output.h): what the summary and stats.json say about the film beyond its last
// frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/outputs/run_output.h"

namespace gb {
namespace {

FrameStats frameAt(double time, float area, float volume, size_t particles, size_t droplets = 0) {
  FrameStats s;
  s.time = time;
  s.area = area;
  s.volume = volume;
  s.particles = particles;
  s.droplets = droplets;
  return s;
}

// The default performance's course in miniature: growth at the wire, pinch-off, a burst by the floor.
RunRecord performanceRecord() {
  RunRecord record;
  record.start(frameAt(0.0, 0.6f, 0.0f, 9500));
  record.addFrame(frameAt(0.1, 1.0f, 0.1f, 9600), 1, 1.0, "film_grown");
  record.addFrame(frameAt(0.2, 2.0f, 0.3f, 9700), 1, 1.0, "film_grown");
  record.addFrame(frameAt(0.3, 3.0f, -0.5f, 9800), 1, 1.0, "film_grown");
  record.addFrame(frameAt(1.0, 2.5f, 0.4f, 9800), 1, 1.0, "pinched_off");
  record.addFrame(frameAt(2.0, 2.4f, 0.4f, 9800), 1, 1.0, "burst_started burst_by_floor");
  record.addFrame(frameAt(2.5, 0.0f, 0.0f, 0, 3000), 1, 1.0, "burst_finished");
  return record;
}

TEST(RunRecord, TheSummaryTellsTheFilmsLifeInOrderAndItsLargestFigures) {
  const std::string story = performanceRecord().story();
  // Exact text: the times are printed to the hundredth, and each event has one phrase.
  EXPECT_NE(story.find("made 0.00 s, grown at the wire on 3 frames (0.10 s to 0.30 s), pinched off 1.00 s, burst "
                       "2.00 s (touched the floor), gone 2.50 s\n"),
            std::string::npos)
      << story;
  // The largest volume is the largest in size whatever its sign (a swept volume changes sign with the side).
  EXPECT_NE(story.find("area 3.0000 m^2 (0.30 s), volume -0.5000 m^3 (0.30 s), 9800 particles, 3000 droplets"),
            std::string::npos)
      << story;
}

TEST(RunRecord, StatsJsonKeepsTheLargestFigures) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "run_record_largest";
  std::filesystem::create_directories(dir);
  performanceRecord().writeJson(dir / "stats.json", "scene", "finished");
  std::ifstream in(dir / "stats.json");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("\"largest\""), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("\"area_time_s\": 0.3"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("\"particles\": 9800"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("\"droplets\": 3000"), std::string::npos) << text.str();
}

TEST(RunRecord, AShowOfManyFilmsIsToldInEightPhrasesAndTheRestCounted) {
  RunRecord record;
  record.start(frameAt(0.0, 1.0f, 0.0f, 100));
  for (int k = 1; k <= 5; ++k) {
    record.addFrame(frameAt(k, 1.0f, 0.0f, 100), 1, 1.0, "burst_started burst_by_poke");
    record.addFrame(frameAt(k + 0.5, 0.0f, 0.0f, 0), 1, 1.0, "burst_finished film_created");
  }
  const std::string story = record.story();
  // 1 + 5 x 3 = 16 phrases: the first 8 told, 8 more counted.
  EXPECT_NE(story.find("burst 1.00 s (poked), gone 1.50 s, made 1.50 s"), std::string::npos) << story;
  EXPECT_NE(story.find(", and 8 more (stats.json)\n"), std::string::npos) << story;
}

}  // namespace
}  // namespace gb
