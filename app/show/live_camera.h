#pragma once
// The live window's camera (giantbubble live): the follow camera of `run --render` (host/render_scene.h's
// FilmFraming: the film framed at about half the image height, eased, led by its drift) so that a free bubble stays
// in the picture until it bursts, or the scene's camera as it is (--camera fixed). While the stage is empty it frames
// the wands instead, as a film would hang from them, so that it is already there when they dip the next film (a
// burst far from where the performance starts). The mouse takes over: a drag or
// the wheel moves the camera from where it is, and it stays where the user put it; Home gives control back, the
// view blending over kHandBack seconds from the user's camera to the followed one, so nothing jumps.

#include <Eigen/Dense>

#include "host/render_scene.h"
#include "model/state.h"
#include "model/wire_frame.h"

namespace gb {

class LiveCamera {
 public:
  static constexpr float kHandBack = 1.0f;  // s: Home blends the user's view into the followed one

  // base: the scene's camera (its direction, and its target and distance when fixed); aspect: image width / height.
  LiveCamera(const OrbitCamera& base, bool follow, float aspect);

  // The camera of the frame `dt` simulated seconds after the last, with `film` and `wands` as they are now. `user`
  // is the window's camera, which the mouse moves: while the camera follows, it is set to the camera shown (so a
  // drag starts from there); once `userMoved`, the user's camera is the one shown until home().
  OrbitCamera update(const State& film, const WandState& wands, float dt, OrbitCamera& user, bool userMoved);
  // Control back to the follow camera (or the scene's, when fixed).
  void home();
  // A new image shape (full screen): the framing starts again at once, as the picture itself changes.
  void setAspect(float aspect);
  [[nodiscard]] bool userControlled() const { return user_; }
  [[nodiscard]] float aspect() const { return aspect_; }

 private:
  OrbitCamera base_;
  bool follow_;
  float aspect_;
  FilmFraming framing_;
  bool user_ = false;            // the user's camera is shown
  OrbitCamera shown_;            // the camera of the last frame
  OrbitCamera handedBack_;       // the user's camera when Home was pressed
  float sinceHome_ = kHandBack;  // s of the blend back so far (kHandBack: none going on)
  State stand_;                  // the wand tips and where a film would hang from them, framed on an empty stage
};

// Where a world point falls in the picture of `camera` (normalized device coordinates: x, y in -1..1 inside it;
// behind the camera: NaN).
Eigen::Vector2f pictureCoordinates(const OrbitCamera& camera, float aspect, const Vec3& point);

}  // namespace gb
