// gb_train_hand_forest: trains the hand forest (hand_forest.h) on fakenect recordings with a ground truth of the
// hands (hands.csv) and writes the model. The model compiled into giantbubble (capture/models/hand_forest.bin)
// is made by the command in docs/capture.md ("The hand forest").
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>

#include "capture/depth_recording.h"
#include "capture/hand_finder.h"
#include "capture/hand_forest_training.h"
#include "capture/output_file.h"

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The performer's depth of every frame with a true hand, segmented as the detector segments it.
void addRecording(const gb::DepthRecording& recording, int frameStep, const gb::ForestTrainingOptions& o,
                  std::mt19937& random, gb::ForestTrainingSet& set) {
  gb::HandFinder finder;
  for (size_t i = 0; i < recording.frames.size() && i < recording.truth.size(); ++i) {
    finder.update(recording.frames[i]);
    if (i % static_cast<size_t>(frameStep) != 0) continue;
    const gb::HandSample& truth = recording.truth[i];
    const std::optional<gb::Vec3d> hands[2] = {
        truth.left.measured ? std::optional<gb::Vec3d>(truth.left.position) : std::nullopt,
        truth.right.measured ? std::optional<gb::Vec3d>(truth.right.position) : std::nullopt};
    if (!hands[0] && !hands[1]) continue;
    gb::addTrainingFrame(finder.detection().body, hands, o, random, set);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gb_train_hand_forest: trains giantbubble's hand forest on recordings with ground-truth hands"};
  std::vector<std::string> recordings;
  std::string out;
  gb::ForestTrainingOptions o;
  app.add_option("recordings", recordings, "fakenect recordings with hands.csv: folders or .tar.gz archives")
      ->required();
  app.add_option("--out", out, "the model file to write")->required();
  app.add_option("--trees", o.trees, "trees")->check(CLI::Range(1, 16));
  app.add_option("--depth", o.maxDepth, "deepest split")->check(CLI::Range(1, 30));
  app.add_option("--features", o.featuresPerNode, "features tried per node")->check(CLI::Range(1, 10000));
  app.add_option("--thresholds", o.thresholdsPerFeature, "thresholds tried per feature")->check(CLI::Range(1, 1000));
  app.add_option("--min-leaf", o.minLeafPixels, "fewest pixels on each side of a split")->check(CLI::Range(1, 100000));
  app.add_option("--body-pixels", o.bodyPixelsPerFrame, "body pixels per frame")->check(CLI::Range(1, 100000));
  app.add_option("--max-offset", o.maxOffset, "largest feature offset (m)")->check(CLI::Range(0.05, 2.0));
  app.add_option("--hand-radius", o.handRadius, "hand label radius (m)")->check(CLI::Range(0.02, 0.3));
  app.add_option("--views", o.otherViews, "other places each frame is also learned from")->check(CLI::Range(0, 10));
  app.add_option("--nearest", o.nearest, "nearest depth of those places (m)")->check(CLI::Range(0.5, 4.0));
  app.add_option("--farthest", o.farthest, "farthest depth of those places (m)")->check(CLI::Range(0.5, 4.5));
  app.add_option("--max-pitch", o.maxPitch, "most camera tilt of those places (degrees down)")
      ->check(CLI::Range(0.0, 45.0));
  app.add_option("--hand-pixels", o.handPixelsPerFrame, "pixels of each hand per frame, at most")
      ->check(CLI::Range(1, 100000));
  app.add_option("--seed", o.seed, "random seed");
  int frameStep = 1;
  app.add_option("--frame-step", frameStep, "learn every N-th frame (neighbouring frames are much alike)")
      ->check(CLI::Range(1, 100));
  CLI11_PARSE(app, argc, argv);

  const auto start = std::chrono::steady_clock::now();
  std::mt19937 random(o.seed);
  gb::ForestTrainingSet set;
  try {
    for (const std::string& path : recordings) addRecording(gb::readDepthRecording(path), frameStep, o, random, set);
  } catch (const gb::HandSourceError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  std::printf("%zu recordings, %zu images, %zu training pixels (%.0f s)\n", recordings.size(), set.images.size(),
              set.pixels.size(), secondsSince(start));
  gb::HandForest forest = gb::trainHandForest(set, o);
  char line[600];
  std::snprintf(line, sizeof line,
                "%zu recordings, every %d. frame, %zu images (mirrored included); %d trees, depth %d, %d features x %d "
                "thresholds, "
                "min leaf %d, %d body and %d hand pixels per frame, offsets up to %.2f m, hand radius %.2f m, %d other "
                "views at %.1f-%.1f m tilted 0-%.0f degrees, seed %u",
                recordings.size(), frameStep, set.images.size(), o.trees, o.maxDepth, o.featuresPerNode,
                o.thresholdsPerFeature, o.minLeafPixels, o.bodyPixelsPerFrame, o.handPixelsPerFrame, o.maxOffset,
                o.handRadius, o.otherViews, o.nearest, o.farthest, o.maxPitch, o.seed);
  forest.trainedOn = line;
  size_t nodes = 0;
  for (const gb::DecisionTree& t : forest.trees) nodes += t.nodes.size();
  const std::vector<uint8_t> bytes = forest.serialize();
  try {
    gb::writeFileAtomically(out, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  } catch (const gb::OutputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  std::printf("%zu nodes, surface to centre %.1f mm, %zu bytes written to %s (%.0f s)\n", nodes,
              1e3 * forest.surfaceToCentre, bytes.size(), out.c_str(), secondsSince(start));
  return 0;
}
