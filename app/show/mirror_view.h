#pragma once
// The mirror view (`--view mirror` of run and live, M in live): the scene seen from the depth camera itself, through
// its intrinsics (kinect_depth.h) from where the calibration puts it in the world, flipped left-right as a mirror
// shows the performer, with the performer drawn in at their own depth (host/camera_layer.h): in the colour camera's
// image registered to the depth where the input has colour (colour_registration.h), else as a shaded silhouette of
// their segmented depth pixels. Behind them the virtual stage, or with --mirror-room the room the camera sees.

#include <optional>
#include <string>

#include "capture/calibration.h"
#include "capture/hand_forest.h"
#include "capture/kinect_depth.h"
#include "host/camera_layer.h"
#include "host/renderer.h"

namespace gb {

class ObservedHandSource;

// The depth camera's view of the world that `calibration` carries its space into.
DepthCameraView mirrorCamera(const Calibration& calibration);

// What the mirror view draws of a depth frame: the performer's pixels (`body`, the segmentation's half-resolution
// depth), and with `room` every other pixel with a reading, at their own depth; coloured by the frame's registered
// colour image when it has one, else shaded by their depth's slope (the performer light, the room grey).
CameraImage cameraImageOf(const kinect::DepthFrame& frame, const BodyDepth& body, bool room);

// The mirror view of a show or a run: whether it is on, and the newest camera image of the input it follows.
class MirrorView {
 public:
  MirrorView(bool on, bool room) : on_(on), room_(room) {}
  // The depth camera whose frames are drawn (nullptr: none, the input is not a depth camera's).
  void attach(ObservedHandSource* source) { source_ = source; }
  // M: on if off and off if on; says what it did.
  std::string toggle();
  [[nodiscard]] bool on() const { return on_; }
  // Turns `frame` into the mirror view when it is on and a depth camera is attached (`calibration`: the input's);
  // the newest depth frame's image is taken when one came since the last call.
  void apply(RenderFrame& frame, const Calibration* calibration);

 private:
  bool on_, room_;
  ObservedHandSource* source_ = nullptr;
  DepthCameraView camera_;
  CameraImage image_;
};

}  // namespace gb
