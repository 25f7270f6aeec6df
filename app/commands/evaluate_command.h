#pragma once
// `giantbubble evaluate`: plays depth recordings that carry a ground truth of the hands (hands.csv beside the
// frames, or --truth) through the hand finder, as fast as it runs, and prints how many true hands were found
// within 10 and 15 cm, the false hands per frame, the frames with the sides swapped and the detection time.
// With --film it plays each recording's hands into a run of a scene instead and prints what the film did
// (film_evaluation.h).

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace gb {

struct EvaluateOptions {
  std::vector<std::string> recordings;         // folders or .tar.gz archives of fakenect recordings
  std::string truth;                           // a trajectory CSV for a single recording without hands.csv
  std::vector<double> depthBand = {0.5, 4.0};  // m
  bool mirrored = false;
  bool perRecording = false;            // a line per recording, not only the total
  std::string forest;                   // a hand forest model file instead of the built-in one
  bool film = false;                    // judge the film the hands make, not the hands
  bool touch = false;                   // judge the performer's touch on a still bubble placed by the ground truth
  bool truthHands = false;              // --film: the recordings' ground-truth hands drive the wands
  std::string scene = "default";        // --film: the scene whose parameters and tool the film has
  std::string stabilizer = "one-euro";  // --film: the stabilizer
  double reach = 2.0;                   // --film: world metres per metre of hand motion
};

CLI::App* addEvaluateCommand(CLI::App& app, EvaluateOptions& options);
int runEvaluate(const EvaluateOptions& options);  // the process exit code

}  // namespace gb
