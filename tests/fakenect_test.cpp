#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "capture/colour_registration.h"
#include "capture/depth_recording.h"
#include "capture/freenect_stream.h"
#include "capture/hand_sources.h"
#include "tests/synthetic_depth.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

// A fresh path under this process's scratch folder, which is removed when the tests end.
fs::path scratch(const std::string& name) {
  static const struct Root {
    fs::path path = fs::temp_directory_path() / ("giantbubble_fakenect_test_" + std::to_string(::getpid()));
    ~Root() { fs::remove_all(path); }
  } root;
  const fs::path dir = root.path / name;
  fs::remove_all(dir);
  fs::create_directories(root.path);
  return dir;
}

// A synthetic session of `frames` depth frames at 30 Hz, written as a fakenect recording.
std::vector<kinect::DepthFrame> writeSession(const fs::path& dir, int frames) {
  FakenectWriter writer(dir);
  std::vector<kinect::DepthFrame> written;
  for (int i = 0; i < frames; ++i) {
    const double t = i / 30.0;
    written.push_back(test::renderPerformer(test::sessionPose(t), t, 1000u + 2000000u * static_cast<uint32_t>(i)));
    writer.write(written.back(), 1700000000.0 + t);
  }
  return written;
}

template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const HandSourceError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Fakenect, ASyntheticSessionPlayedThroughLibfreenectsFakenectGivesTheSameHands) {
  const fs::path dir = scratch("session");
  const std::vector<kinect::DepthFrame> frames = writeSession(dir, 12);

  // Straight from the frames, without libfreenect.
  HandFinder direct;
  std::vector<HandSample> expected;
  for (const kinect::DepthFrame& f : frames) expected.push_back(direct.update(f));

  // Through fakenect, the code path of a live camera.
  DepthHandSource played(DepthStream::openRecording(dir), DetectionOptions{}, TrackerOptions{});
  EXPECT_NE(played.describe().find("12 depth frames"), std::string::npos) << played.describe();
  std::vector<uint16_t> firstRaw;
  played.onFrame([&](const kinect::DepthFrame& f) {
    if (firstRaw.empty()) firstRaw = f.raw;
  });
  for (size_t i = 0; i < expected.size(); ++i) {
    const std::optional<HandSample> s = played.next();
    ASSERT_TRUE(s) << "frame " << i;
    EXPECT_NEAR(s->time, expected[i].time, 1e-5);  // from the file names, microseconds
    ASSERT_TRUE(s->left.measured && s->right.measured) << i;
    EXPECT_EQ(s->left.position, expected[i].left.position) << i;
    EXPECT_EQ(s->right.position, expected[i].right.position) << i;
    // And those are the hands of the session, within 2 cm.
    const test::SyntheticPerformer pose = test::sessionPose(frames[i].time);
    EXPECT_LT((s->left.position - *pose.leftHand).norm(), 0.02) << i;
    EXPECT_LT((s->right.position - *pose.rightHand).norm(), 0.02) << i;
  }
  EXPECT_EQ(firstRaw, frames.front().raw);
  EXPECT_FALSE(played.next());  // the end of the recording, without fakenect's complaint
}

// A recording's 'a' entries (fakenect-record's accelerometer dumps) reach the detector as gravity. A
// camera tilted 15 degrees down: each played frame carries the accelerometer's up within 0.2
// degrees (the raw counts' rounding, 1/819 g, is 0.07 degrees), and the floor is fitted along it, its height
// within 3 cm (two 3 cm height bins). An accelerometer reading upside down is not believed: the floor is then
// searched for, as without one.
TEST(Fakenect, TheAccelerometerOfARecordingGivesTheFloorItsGravity) {
  test::SceneOptions options;
  options.cameraPitch = 15.0;
  options.cameraHeight = test::cameraHeightFor(15.0, 2.5);
  options.noise = false;
  const test::SyntheticScene scene = test::renderScene(test::namedPose("forward"), options);
  const Vec3d up = scene.up;
  const fs::path dir = scratch("accelerometer");
  {
    FakenectWriter writer(dir);
    for (int i = 0; i < 4; ++i) {
      kinect::DepthFrame frame = scene.frame;
      frame.gravityUp = up;
      writer.write(frame, 1700000000.0 + i / 30.0);
    }
  }
  std::ifstream index(dir / "INDEX.txt");
  std::string line;
  int accelerometerEntries = 0;
  while (std::getline(index, line)) accelerometerEntries += line.rfind("a-", 0) == 0;
  EXPECT_EQ(accelerometerEntries, 4);

  auto stream = DepthStream::openRecording(dir);
  kinect::DepthFrame played;
  int frames = 0;
  while (stream->poll(played, 0.1) == DepthStream::Poll::Frame) {
    ++frames;
    ASSERT_TRUE(played.gravityUp) << frames;
    EXPECT_LT(std::acos(std::min(1.0, played.gravityUp->dot(up))) * 180.0 / kPi, 0.2) << frames;
    const Detection d = detectHands(played, DetectionOptions{});
    ASSERT_TRUE(d.floor);
    EXPECT_LT((d.floor->up - *played.gravityUp).norm(), 1e-12);  // a measured gravity is the floor's normal
    EXPECT_NEAR(-d.floor->offset, scene.floorDistance, 0.03);
  }
  EXPECT_EQ(frames, 4);

  EXPECT_FALSE(kinect::accelToCameraUp(0.0, -kinect::kStandardGravity, 0.0));       // upside down
  EXPECT_FALSE(kinect::accelToCameraUp(0.0, 0.2 * kinect::kStandardGravity, 0.0));  // falling, or no reading
  const std::array<int16_t, 3> level = kinect::cameraUpToAccel(Vec3d::UnitY());
  EXPECT_EQ(level[1], 819);
}

// An accelerometer read with its pitch's sign the wrong way (a camera tilted 13 degrees down taken for 13 up)
// still gathers a slanted strip of the floor along it, so the detector alone cannot tell; the source checks it
// against the floor found without it, warns once and finds the floor from the depth: both hands are found.
// A right reading raises no warning.
TEST(Fakenect, AnAccelerometerThatDisagreesWithTheFloorIsNotBelieved) {
  test::SceneOptions options;
  options.cameraPitch = 13.0;
  options.cameraHeight = test::cameraHeightFor(13.0, 2.5);
  const test::SyntheticScene scene = test::renderScene(test::namedPose("forward"), options);
  for (const bool wrong : {true, false}) {
    const fs::path dir = scratch(wrong ? "wrong_accelerometer" : "right_accelerometer");
    {
      FakenectWriter writer(dir);
      for (int i = 0; i < 3; ++i) {
        kinect::DepthFrame frame = scene.frame;
        frame.gravityUp = wrong ? Vec3d(scene.up.x(), scene.up.y(), -scene.up.z()) : scene.up;
        writer.write(frame, 1700000000.0 + i / 30.0);
      }
    }
    DepthHandSource played(DepthStream::openRecording(dir), DetectionOptions{}, TrackerOptions{});
    std::vector<std::string> messages;
    for (int i = 0; i < 3; ++i) {
      const std::optional<HandSample> s = played.next();
      ASSERT_TRUE(s);
      EXPECT_TRUE(s->left.measured && s->right.measured) << wrong << " " << i;
      for (const std::string& m : played.takeMessages()) messages.push_back(m);
    }
    ASSERT_EQ(messages.size(), wrong ? 1u : 0u) << (messages.empty() ? "" : messages.front());
    if (wrong) {
      EXPECT_NE(messages.front().find("26 degrees from the floor in view"), std::string::npos) << messages.front();
    }
  }
}

TEST(Fakenect, RecordingsPlayOneAfterAnotherInOneProcess) {
  const fs::path a = scratch("first"), b = scratch("second");
  writeSession(a, 2);
  FakenectWriter writer(b);
  test::SyntheticPerformer still;
  writer.write(test::renderPerformer(still), 5.0);
  for (int round = 0; round < 2; ++round) {
    auto first = DepthStream::openRecording(a);
    EXPECT_THROW(DepthStream::openRecording(b), HandSourceError);  // fakenect's globals: one at a time
    kinect::DepthFrame f;
    EXPECT_EQ(first->poll(f, 1.0), DepthStream::Poll::Frame);
    first.reset();
    auto second = DepthStream::openRecording(b);
    EXPECT_EQ(second->poll(f, 1.0), DepthStream::Poll::Frame);
    EXPECT_EQ(f.raw, test::renderPerformer(still).raw);  // the second recording, from its first frame
    EXPECT_EQ(second->poll(f, 1.0), DepthStream::Poll::End);
  }
}

TEST(Fakenect, BadRecordingsAreClearErrorsBeforeFakenectSeesThem) {
  EXPECT_NE(errorOf([] { DepthStream::openRecording(scratch("absent")); }).find("does not exist"), std::string::npos);

  const fs::path empty = scratch("empty");
  fs::create_directories(empty);
  EXPECT_NE(errorOf([&] { DepthStream::openRecording(empty); }).find("no INDEX.txt"), std::string::npos);
  std::ofstream(empty / "INDEX.txt").flush();
  EXPECT_NE(errorOf([&] { DepthStream::openRecording(empty); }).find("empty recording"), std::string::npos);

  const fs::path truncated = scratch("truncated");
  writeSession(truncated, 3);
  const std::string second = [&] {
    std::ifstream index(truncated / "INDEX.txt");
    std::string line;
    std::getline(index, line);
    std::getline(index, line);
    return line;
  }();
  fs::resize_file(truncated / second, 1000);
  const std::string message = errorOf([&] { DepthStream::openRecording(truncated); });
  EXPECT_NE(message.find("line 2"), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;

  fs::remove(truncated / second);
  EXPECT_NE(errorOf([&] { DepthStream::openRecording(truncated); }).find("does not exist"), std::string::npos);

  std::ofstream(truncated / "INDEX.txt") << "not a fakenect line\n";
  EXPECT_NE(errorOf([&] { DepthStream::openRecording(truncated); }).find("not a fakenect entry"), std::string::npos);

  EXPECT_NE(errorOf([] { FakenectWriter writer(fs::temp_directory_path()); }).find("not an empty folder"),
            std::string::npos);
}

TEST(Fakenect, AFileGoneMidPlaybackIsALostInputNotACrash) {
  const fs::path dir = scratch("vanishing");
  writeSession(dir, 3);
  DepthHandSource played(DepthStream::openRecording(dir), DetectionOptions{}, TrackerOptions{});
  ASSERT_TRUE(played.next());
  fs::remove_all(dir);  // fakenect itself would exit() reading the next file
  EXPECT_THROW(played.next(), HandSourceLost);
}

TEST(Kinect, WithoutACameraTheLiveSourceSaysNoKinectFound) {
  std::unique_ptr<DepthStream> stream;
  try {
    stream = DepthStream::openKinect();
  } catch (const HandSourceError& e) {
    EXPECT_NE(std::string(e.what()).find("no Kinect found"), std::string::npos) << e.what();
    EXPECT_NE(errorOf([] { makeHandSource("kinect", SourceOptions{}); }).find("no Kinect found"), std::string::npos);
    return;
  }
  GTEST_SKIP() << "a Kinect is plugged in: " << stream->describe();
}

}  // namespace
}  // namespace gb

namespace gb {
namespace {

// The recording's INDEX.txt lines, and the first depth file's name.
std::vector<std::string> indexLines(const fs::path& dir) {
  std::ifstream in(dir / "INDEX.txt");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A Kinect unplugged mid-performance and plugged back in, through a stand-in for the live libfreenect
// (fake_freenect.cpp). Unplugged, the source is lost and no Kinect is found; plugged back, it opens again while
// the lost source still exists (the live window opens the new input before it drops the old one), which needs
// the lost device let go of: a device still open in the process cannot be claimed again.
TEST(Kinect, AnUnpluggedCameraIsLostAndOpensAgainWhenItIsBack) {
  const fs::path dir = scratch("fake_kinect");
  writeSession(dir / "frame", 1);
  std::string frameFile;
  for (const auto& entry : fs::directory_iterator(dir / "frame"))
    if (entry.path().filename().string().rfind("d-", 0) == 0) frameFile = entry.path().string();
  const fs::path unplugged = dir / "unplugged";
  setenv("GIANTBUBBLE_FREENECT_LIBRARY", GB_FAKE_FREENECT, 1);
  setenv("GB_FAKE_KINECT_FRAME", frameFile.c_str(), 1);
  setenv("GB_FAKE_KINECT_UNPLUGGED_IF", unplugged.c_str(), 1);
  auto open = [] {
    return std::make_unique<DepthHandSource>(DepthStream::openKinect(), DetectionOptions{}, TrackerOptions{});
  };
  auto bothHands = [](HandSource& source) {
    for (int i = 0; i < 5; ++i) {  // a late frame is a sample with both hands held: give it a few
      const std::optional<HandSample> s = source.next();
      if (s && s->left.measured && s->right.measured) return true;
    }
    return false;
  };

  auto source = open();
  std::optional<Vec3d> gravity;
  source->onFrame([&](const kinect::DepthFrame& f) { gravity = f.gravityUp; });
  EXPECT_TRUE(bothHands(*source));
  ASSERT_TRUE(gravity);  // the accelerometer, read through the motor subdevice: level
  EXPECT_LT((*gravity - Vec3d::UnitY()).norm(), 1e-9);

  std::ofstream(unplugged).put('\n');
  EXPECT_THROW(source->next(), HandSourceLost);
  EXPECT_NE(errorOf([] { DepthStream::openKinect(); }).find("no Kinect found"), std::string::npos);

  fs::remove(unplugged);
  std::unique_ptr<DepthHandSource> again;
  EXPECT_NO_THROW(again = open()) << errorOf([&] { open(); });
  if (again) {
    EXPECT_TRUE(bothHands(*again));
  }
  source.reset();  // the old input goes after the new one came, as in the live window
  if (again) {
    EXPECT_TRUE(bothHands(*again));
  }
  unsetenv("GIANTBUBBLE_FREENECT_LIBRARY");
  unsetenv("GB_FAKE_KINECT_FRAME");
  unsetenv("GB_FAKE_KINECT_UNPLUGGED_IF");
}

TEST(Fakenect, APauseLongerThanTheLimitIsRefusedBeforeFakenectSleepsThroughIt) {
  const fs::path dir = scratch("gap");
  {
    FakenectWriter writer(dir);
    writer.write(test::renderPerformer(test::sessionPose(0.0), 0.0, 1000u), 1700000000.0);
    writer.write(test::renderPerformer(test::sessionPose(0.1), 0.1, 2000u), 1700000000.0 + kMaxFakenectGap + 5.0);
  }
  const std::string message = errorOf([&] { (void)readFakenectIndex(dir); });
  EXPECT_NE(message.find("jumps 15 s forward"), std::string::npos) << message;
  EXPECT_NE(message.find("at most 10 s between entries"), std::string::npos) << message;
}

TEST(Fakenect, CrLfLineEndingsAndAForeignFrameHeaderAreNamed) {
  const fs::path dir = scratch("crlf");
  writeSession(dir, 2);
  const std::vector<std::string> lines = indexLines(dir);
  {
    std::ofstream index(dir / "INDEX.txt", std::ios::trunc);
    for (const std::string& line : lines) index << line << "\r\n";
  }
  std::string message = errorOf([&] { (void)readFakenectIndex(dir); });
  EXPECT_NE(message.find("line 1: the line ends in a carriage return"), std::string::npos) << message;

  {
    std::ofstream index(dir / "INDEX.txt", std::ios::trunc);
    for (const std::string& line : lines) index << line << "\n";
  }
  // The same byte count as a Kinect frame, but an ASCII greymap header: fakenect would read it as depth.
  std::fstream frame(dir / lines.front(), std::ios::in | std::ios::out | std::ios::binary);
  frame.write("P2", 2);
  frame.close();
  message = errorOf([&] { (void)readFakenectIndex(dir); });
  EXPECT_NE(message.find("has the header 'P2 640 480 65535', expected 'P5 640 480 65535'"), std::string::npos)
      << message;
}

// A device.json as fakenect records libfreenect's registration (the fields giantbubble reads; docs/formats.md).
const char* const kDeviceJson =
    R"({"zero_plane_info": {"dcmos_rcmos_dist": 2.4, "reference_distance": 120.0, "reference_pixel_size": 0.1042}})";

// A depth frame and a colour image with a pattern in it: red increasing across, green down, blue 77.
kinect::DepthFrame colouredFrame(uint32_t timestamp) {
  kinect::DepthFrame frame;
  frame.timestamp = timestamp;
  for (size_t i = 0; i < frame.raw.size(); ++i) frame.raw[i] = kinect::metresToRaw(2.0);
  frame.colour.resize(static_cast<size_t>(kinect::kColourBytes));
  for (int v = 0; v < kinect::kHeight; ++v)
    for (int u = 0; u < kinect::kWidth; ++u) {
      const size_t i = 3 * (static_cast<size_t>(v) * kinect::kWidth + static_cast<size_t>(u));
      frame.colour[i] = static_cast<uint8_t>(u % 256);
      frame.colour[i + 1] = static_cast<uint8_t>(v % 256);
      frame.colour[i + 2] = 77;
    }
  return frame;
}

TEST(ColourCapture, ARecordingKeepsItsColourFramesAndDeviceJsonAndPlaysThemBack) {
  const fs::path dir = scratch("coloured");
  kinect::DepthFrame frame = colouredFrame(1000);
  auto registration = std::make_shared<ColourRegistration>(registrationFromDeviceJson(kDeviceJson, "device.json"));
  frame.registration = registration;
  {
    FakenectWriter writer(dir);
    writer.write(frame, 1700000000.0);
    frame.timestamp = 2000;
    writer.write(frame, 1700000000.0 + 1.0 / 30.0);
  }
  ASSERT_TRUE(fs::exists(dir / "device.json"));
  std::ifstream index(dir / "INDEX.txt");
  std::string first;
  std::getline(index, first);
  EXPECT_EQ(first.substr(0, 2), "r-");  // the colour image before its depth frame, as fakenect-record writes them

  // Read straight from the files.
  const DepthRecording read = readDepthRecording(dir);
  ASSERT_EQ(read.frames.size(), 2u);
  EXPECT_EQ(read.frames[1].colour, frame.colour);
  ASSERT_TRUE(read.frames[1].registration);
  EXPECT_DOUBLE_EQ(read.frames[1].registration->translation.x(), 0.024);  // 2.4 cm

  // Played through Debian's fakenect, the code path of a live camera.
  std::unique_ptr<DepthStream> stream = DepthStream::openRecording(dir);
  kinect::DepthFrame played;
  ASSERT_EQ(stream->poll(played, 1.0), DepthStream::Poll::Frame);
  EXPECT_EQ(played.colour, frame.colour);
  ASSERT_TRUE(played.registration);
  EXPECT_NE(played.registration->source.find("device.json"), std::string::npos);
  EXPECT_EQ(played.raw, frame.raw);
}

TEST(ColourCapture, ARecordingWithoutColourGivesFramesWithoutIt) {
  const fs::path dir = scratch("depth_only");
  kinect::DepthFrame frame = colouredFrame(1000);
  frame.colour.clear();
  FakenectWriter(dir).write(frame, 1700000000.0);
  const DepthRecording read = readDepthRecording(dir);
  ASSERT_EQ(read.frames.size(), 1u);
  EXPECT_TRUE(read.frames[0].colour.empty());
  EXPECT_FALSE(read.frames[0].registration);
}

TEST(ColourCapture, ATruncatedColourFileIsNamedBeforeFakenectReadsIt) {
  const fs::path dir = scratch("truncated_colour");
  FakenectWriter(dir).write(colouredFrame(1000), 1700000000.0);
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().rfind("r-", 0) == 0) fs::resize_file(entry.path(), 1000);
  EXPECT_NE(errorOf([&] { readFakenectIndex(dir); }).find("is truncated"), std::string::npos);
}

}  // namespace
}  // namespace gb
