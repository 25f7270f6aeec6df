#pragma once
// How a film fares under a real performer's hands: `giantbubble evaluate --film` plays each depth recording's hands
// (found in its depth by the hand finder, or its ground truth with --truth-hands) through the stabilizer and the
// calibration into a run of a scene, as `giantbubble run --input fakenect:DIR` does but as fast as it runs, and
// reports what the film did: how long it lived, whether it lived to the end or pinched off into a free bubble, how far
// it grew, and how far the wands lag behind the hands (docs/capture.md, "Films under real hands").

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "app/commands/run_command.h"
#include "capture/depth_recording.h"
#include "capture/hand_finder.h"

namespace gb {

// How one recording's film ended.
struct FilmLife {
  std::string recording;
  double length = 0;         // s of the run: the recording from the frame with both hands found to its end
  double life = 0;           // s until the film (or the free bubble it pinched off into) started to burst, else length
  bool pinchedOff = false;   // it closed into a free bubble before any burst
  std::string burstCause;    // the first burst's cause (bursting.h's names: "thinning", "impact", ...), else empty
  double startArea = 0;      // m^2, the film as dipped
  double peakArea = 0;       // m^2, the largest the film (or bubble) was
  double lag = 0;            // s: the wands behind the input's hands (the hand that moved more)
  double peakWandSpeed = 0;  // m/s, world space: the faster wand tip at its fastest
  [[nodiscard]] bool survived() const { return pinchedOff || burstCause.empty(); }
  [[nodiscard]] double lifeShare() const { return length > 0 ? life / length : 0.0; }
  [[nodiscard]] double growth() const { return startArea > 0 ? peakArea / startArea : 0.0; }
};

struct FilmEvaluationOptions {
  RunOptions run;              // the scene: parameters, tool, reach and stabilizer (run.input)
  DetectionOptions detection;  // the hand finder, when the hands are found in the depth
  TrackerOptions tracker;
  bool truthHands = false;  // drive the wands by the recording's ground truth (hands.csv) instead
};

// Plays one recording. Throws HandSourceError when it has no hands to play (no ground truth with truthHands).
FilmLife playFilmOnRecording(const DepthRecording& recording, const FilmEvaluationOptions& options);

// The figures over many recordings.
struct FilmLifeSummary {
  size_t recordings = 0;
  double survivedShare = 0;  // lived to the end, or pinched off
  double medianLifeShare = 0;
  double medianGrowth = 0;  // peak area / start area
  double medianLag = 0;     // s
};
FilmLifeSummary summarize(const std::vector<FilmLife>& lives);

// The performer's touch on real depth (`giantbubble evaluate --touch`): a still free bubble (--bubble-at) placed in a
// recording's camera space, the performer's body from its depth as the collider. Where the bubble goes depends on the
// action: at the farthest-forward point of a true hand in one that reaches out (a push, a punch, a knock), where the
// touch must burst it as the hand enters; at least kAwayFromHands from every true hand in one that does not (a wave,
// a clap, a circle), where nothing may.
enum class TouchTrialKind { Reach, Away };

// UTD-MHAD's actions (the recordings' aA prefix) of each kind: 13 front boxing, 18 two-hand push, 19 knock on door;
// 3 hand wave, 4 two-hand clap, 9 and 10 circles. Nothing for the others.
std::optional<TouchTrialKind> touchTrialKindOf(const std::string& recording);

struct TouchTrial {
  std::string recording;
  TouchTrialKind kind = TouchTrialKind::Reach;
  std::array<double, 3> bubbleAt{};  // camera space (m)
  double entry = 0;                  // Reach: run time (s) the true hand came within the bubble's radius of its centre
  std::optional<double> touchBurst;  // run time (s) the body's touch burst it, if it did
  std::string otherBurst;            // the cause of a burst by anything else first ("wand", "floor", ...)
  // Reach: burst by the touch from kEarliestTouch before the hand's entry to kLatestTouch after it. Away: no touch.
  [[nodiscard]] bool passed() const;

  static constexpr double kBubbleRadius = 0.15;  // m of camera space
  static constexpr double kAwayFromHands = 0.5;  // m: an Away bubble's centre from every true hand position
  static constexpr double kEarliestTouch = 0.3;  // s before the entry: the hand's front surface leads its joint
  static constexpr double kLatestTouch = 0.2;    // s after it: a depth frame, the step and the burst's start
};

// Plays one recording's depth (the hands found in it, the body as the collider) against its bubble; throws
// HandSourceError when it has no ground truth or its action is of neither kind.
TouchTrial playTouchOnRecording(const DepthRecording& recording, const FilmEvaluationOptions& options);

}  // namespace gb
