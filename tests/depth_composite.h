#pragma once
// Real recorded performers in rooms they were not recorded in: the people of a recording whose background was
// removed (no reading around them) are cut out as 3D points, optionally moved nearer or farther and seen by a
// camera tilted down, and put into a synthetic room (synthetic_depth.h) with its own Kinect noise, optionally
// with a second person at the edge of the view and the empty room seen first. Their ground-truth hands move
// with them; a true hand the move takes out of the image is no longer measured in the truth (no camera could see
// it), but a hand reported near it is not false.
// gb_hands_bench and the hand evaluation tests judge the detector on these (docs/capture.md).

#include <string>

#include "capture/depth_recording.h"

namespace gb::test {

struct CompositeOptions {
  std::string room = "living-room";           // a layout of roomLayouts()
  double distance = 0.0;                      // m: the performer's median depth is moved here (0: kept as recorded)
  double pitch = 0.0;                         // degrees the camera is tilted down
  int emptyFrames = 0;                        // frames of the empty room before the recording: the performer steps in
  const DepthRecording* bystander = nullptr;  // a second person, at the edge of the view
  unsigned seed = 1;
};

DepthRecording composite(const DepthRecording& performer, const CompositeOptions& options);

// A short name of the options, e.g. "office, 1.2 m, tilt 13, steps in, bystander".
std::string describe(const CompositeOptions& options);

}  // namespace gb::test
