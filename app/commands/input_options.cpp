#include "app/commands/input_options.h"

#include <cstring>
#include <optional>
#include <stdexcept>
#include <utility>

#include "app/commands/cli_checks.h"
#include "app/commands/interrupt.h"
#include "capture/threaded_hand_source.h"
#include "capture/trajectory_file.h"
#include "capture/untrusted.h"

namespace gb {

namespace {

// X,Y,Z in metres with Z > 0, each coordinate a finite decimal number; nothing, with `why` (`expected` and what was
// given), when `text` is not one.
std::optional<Vec3d> cameraPoint(const std::string& text, const std::string& expected, std::string& why) {
  std::vector<std::string> fields(1);
  for (const char c : text) {
    if (c == ',')
      fields.emplace_back();
    else
      fields.back().push_back(c);
  }
  why = expected + "; got '" + printable(text) + "'";
  if (fields.size() != 3) return std::nullopt;
  Vec3d p;
  for (int k = 0; k < 3; ++k) {
    if (const std::string problem = numberProblem(fields[static_cast<size_t>(k)], p[k]); !problem.empty()) {
      why += ": " + problem;
      return std::nullopt;
    }
  }
  if (!(p.z() > 0.0 && p.norm() <= kMaxHandDistance)) return std::nullopt;
  return p;
}

constexpr const char* kPerformerExpected = "--performer: expected X,Y,Z in metres with Z > 0, or auto";
constexpr const char* kBubbleExpected = "--bubble-at: expected X,Y,Z in metres with Z > 0";

std::optional<Vec3d> performerPoint(const std::string& text, std::string& why) {
  return cameraPoint(text, kPerformerExpected, why);
}

}  // namespace

void addDepthBandOption(CLI::App* command, std::vector<double>& band) {
  command->add_option("--depth-band", band, "NEAR FAR: depths (m) where the performer is looked for")
      ->expected(2)
      ->check(FiniteRange(0.3, 10.0));
}

void addInputOptions(CLI::App* command, InputOptions& o) {
  command
      ->add_option("--input", o.input,
                   "where the hands come from: kinect, fakenect:DIR, trajectory:FILE or script:NAME "
                   "(default: the scene's, script:giant for the default scene)")
      ->check(NotEmpty());
  command->add_option("--gesture", o.gesture, "scripted wand gesture, the same as --input script:NAME")
      ->check(CLI::IsMember(gestureNames()))
      ->excludes("--input");
  command->add_option("--stabilizer", o.stabilizer, "hand stabilizer for camera and file inputs")
      ->check(CLI::IsMember({"bspline", "one-euro"}));
  command
      ->add_option("--performer", o.performer,
                   "camera-space point X,Y,Z (m) between the performer's resting hands, or auto (the first "
                   "sample with both hands, when the performer is found); default auto for kinect and "
                   "fakenect:DIR, else 0,0,2")
      ->check([](const std::string& text) {
        std::string why;
        return text == "auto" || performerPoint(text, why) ? std::string() : why.substr(std::strlen("--performer: "));
      });
  command->add_option("--reach", o.reach, "world metres per metre of hand motion")->check(FiniteRange(0.1, 20.0));
  command->add_option("--camera-pitch", o.cameraPitch, "degrees the camera is tilted up")
      ->check(FiniteRange(-45.0, 45.0));
  addDepthBandOption(command, o.depthBand);
  command->add_flag("--mirrored", o.mirrored, "the depth image is mirrored (the performer's left hand on its left)");
}

void addBubbleOptions(CLI::App* command, InputOptions& o) {
  command
      ->add_option_function<std::string>(
          "--bubble-at",
          [&o](const std::string& text) {
            std::string why;
            const std::optional<Vec3d> p = cameraPoint(text, kBubbleExpected, why);
            if (!p) throw CLI::ValidationError("--bubble-at", why.substr(std::strlen("--bubble-at: ")));
            o.bubbleAt = std::array<double, 3>{p->x(), p->y(), p->z()};
          },
          "a still free bubble centred at camera-space X,Y,Z (m), mapped into the world as the hands are: it floats "
          "there until something touches it (rehearsal and tests of the performer's touch)")
      ->check(NotEmpty());
  command->add_option("--bubble-radius", o.bubbleRadius, "the --bubble-at bubble's radius in camera space (m)")
      ->check(FiniteRange(0.02, 1.0));
}

bool isCamera(const std::string& spec) { return spec == "kinect" || spec.rfind("fakenect:", 0) == 0; }

Calibration calibrationOf(const InputOptions& o) {
  Calibration c;
  c.reach = o.reach;
  c.cameraPitch = o.cameraPitch;
  if (o.performer == "auto" || (o.performer.empty() && isCamera(o.spec()))) {
    c.autoPerformer = true;
    return c;
  }
  std::string why;
  const std::optional<Vec3d> point = performerPoint(o.performer.empty() ? "0,0,2" : o.performer, why);
  if (!point) throw std::invalid_argument(why);
  c.performer = *point;
  return c;
}

SourceOptions sourceOptionsOf(const InputOptions& o, const GestureOptions& gesture) {
  if (o.depthBand.size() != 2 || o.depthBand[0] >= o.depthBand[1])
    throw std::invalid_argument("--depth-band: expected NEAR FAR with NEAR < FAR");
  SourceOptions s;
  s.detection.segmentation.nearLimit = static_cast<float>(o.depthBand[0]);
  s.detection.segmentation.farLimit = static_cast<float>(o.depthBand[1]);
  s.tracker.mirrored = o.mirrored;
  s.calibration = calibrationOf(o);
  s.gesture = gesture;
  s.trajectory.seconds = o.runSeconds + 1.0;  // a second more for the stabilizer to end on
  return s;
}

StabilizerOptions stabilizerOptionsOf(const InputOptions& o) {
  StabilizerOptions s;
  s.kind = stabilizerFromName(o.stabilizer);
  return s;
}

std::unique_ptr<WandInput> makeWandInput(const InputOptions& o, const GestureOptions& gesture, PerformerWait wait,
                                         const HandSourceWrapper& wrap) {
  const std::string spec = o.spec();
  if (spec == "mouse")
    throw HandSourceError("the mouse moves the wands in the live window only: giantbubble live --input mouse");
  if (o.scripted()) {
    try {
      return std::make_unique<ScriptedWands>(gestureFromName(spec.substr(7)), gesture);
    } catch (const std::invalid_argument& e) {
      throw HandSourceError(e.what());
    }
  }
  const SourceOptions source = sourceOptionsOf(o, gesture);
  // The film is made on the performer's hands: camera inputs and trajectories start when both hands are seen.
  wait.enabled = source.calibration.autoPerformer || spec.rfind("trajectory:", 0) == 0;
  if (!wait.cancelled) wait.cancelled = [] { return InterruptCatcher::requested(); };  // Ctrl-C while waiting
  std::unique_ptr<HandSource> hands = makeHandSource(spec, source);
  if (wrap) hands = wrap(std::move(hands));
  if (isCamera(spec)) hands = std::make_unique<ThreadedHandSource>(std::move(hands));
  auto wands = std::make_unique<StabilizedWands>(std::move(hands), stabilizerOptionsOf(o), source.calibration, wait);
  wands->followWallClock(o.wallClock);
  return wands;
}

}  // namespace gb
