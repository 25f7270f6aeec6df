// The hand detector and tracker on synthetic Kinect v1 depth (tests/synthetic_depth.h): an articulated body of
// capsules in every benchmark motion, a camera tilted 0, 10 and 20 degrees down with the floor in view, a chair,
// a table and a wall behind, Kinect noise, quantisation and no-reading holes. Prints, per motion and overall,
// the fraction of expected hands found within 10 cm on their own side, false hands per frame (a reported hand
// more than 10 cm from its own true hand) and identity swaps per minute (a reported hand that lies within
// 10 cm of the other true hand instead, counted once per swap).
//
// Run: ./build/bench/gb_depth_bench [--seconds S] [--png DIR] [--accelerometer]
//   S seconds of each motion at each tilt (default 4); --accelerometer gives each frame the scene's gravity, as
//   a live Kinect or a recording with 'a-' entries does (the floor is then not searched for).
// Targets (issue 15): >= 95% found, <= 0.02 false hands per frame, 0 swaps in the crossing motion.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "capture/depth_plot.h"
#include "capture/hand_finder.h"
#include "tests/synthetic_depth.h"

namespace {

using namespace gb;

struct Tally {
  int expected = 0, found = 0, frames = 0, falseHands = 0, swaps = 0;
  double detectSeconds = 0.0;
  void add(const Tally& t) {
    expected += t.expected, found += t.found, frames += t.frames, falseHands += t.falseHands, swaps += t.swaps;
    detectSeconds += t.detectSeconds;
  }
  void print(const std::string& name) const {
    const double minutes = frames / 30.0 / 60.0;
    std::printf("%-14s %6d %7.1f%% %10.3f %10.1f %9.1f\n", name.c_str(), frames, 100.0 * found / std::max(1, expected),
                static_cast<double>(falseHands) / std::max(1, frames), swaps / std::max(minutes, 1e-9),
                1e3 * detectSeconds / std::max(1, frames));
  }
};

Tally runSequence(const std::string& sequence, double pitch, double distance, double seconds, const std::string& pngDir,
                  bool accelerometer) {
  test::SceneOptions scene;
  scene.cameraPitch = pitch;
  scene.cameraHeight = test::cameraHeightFor(pitch, distance);
  scene.wallDistance = distance + 1.0;
  HandFinder finder;
  Tally tally;
  bool swapped[2] = {false, false};
  const int frames = static_cast<int>(seconds * 30.0);
  for (int i = 0; i < frames; ++i) {
    const double t = i / 30.0;
    test::BodyPose pose = test::sequencePose(sequence, t);
    pose.feet.z() = distance;
    scene.seed = static_cast<unsigned>(i + 1);
    test::SyntheticScene s = test::renderScene(pose, scene, t);
    if (accelerometer) s.frame.gravityUp = s.up;
    const auto start = std::chrono::steady_clock::now();
    const HandSample out = finder.update(s.frame);
    const Detection& d = finder.detection();
    tally.detectSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++tally.frames;
    const Vec3d truth[2] = {s.leftHand, s.rightHand};
    for (int h = 0; h < 2; ++h) {
      const Hand hand = h == 0 ? Hand::Left : Hand::Right;
      const HandObservation& o = out.hand(hand);
      const bool own = o.measured && (o.position - truth[h]).norm() < 0.1;
      if (test::presented(sequence, hand)) ++tally.expected, tally.found += own;
      if (o.measured && !own) ++tally.falseHands;
      const bool isSwapped = o.measured && !own && (o.position - truth[1 - h]).norm() < 0.1;
      if (isSwapped && !swapped[h]) ++tally.swaps;
      swapped[h] = isSwapped;
    }
    if (!pngDir.empty() && i % 15 == 0) {
      char name[128];
      std::snprintf(name, sizeof name, "%s-%02.0f-%03d.png", sequence.c_str(), pitch, i);
      writeDepthPlot(std::filesystem::path(pngDir) / name, s.frame, d, out);
    }
  }
  // A swap shows on both hands at once: count it once.
  tally.swaps = (tally.swaps + 1) / 2;
  return tally;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 4.0;
  std::string pngDir;
  bool accelerometer = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seconds" && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else if (a == "--png" && i + 1 < argc) {
      pngDir = argv[++i];
      std::filesystem::create_directories(pngDir);
    } else if (a == "--accelerometer") {
      accelerometer = true;
    } else {
      std::fprintf(stderr, "usage: %s [--seconds S] [--png DIR] [--accelerometer]\n", argv[0]);
      return 2;
    }
  }
  if (!(seconds > 0.0)) {
    std::fprintf(stderr, "error: --seconds must be positive\n");
    return 2;
  }
  std::printf("%-14s %6s %8s %10s %10s %9s\n", "motion", "frames", "found", "false/fr", "swaps/min", "ms/frame");
  Tally all;
  int index = 0;
  for (const std::string& sequence : test::sequenceNames()) {
    Tally motion;
    for (const double pitch : {0.0, 10.0, 20.0}) {
      const double distance = 2.3 + 0.2 * (index++ % 3);
      motion.add(runSequence(sequence, pitch, distance, seconds, pngDir, accelerometer));
    }
    motion.print(sequence);
    all.add(motion);
  }
  all.print("all");
  return 0;
}
