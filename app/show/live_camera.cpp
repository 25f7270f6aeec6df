#include "app/show/live_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace gb {

namespace {

FilmFraming framingFor(float aspect) {
  FilmFraming::Options options;
  options.aspect = aspect;
  return FilmFraming(options);
}

// `a` blended into `b` by s in 0..1: the target and the angles linearly (the yaw the short way round), the
// distance geometrically, as a zoom feels even.
OrbitCamera blend(const OrbitCamera& a, const OrbitCamera& b, float s) {
  OrbitCamera c = b;
  c.target = a.target + s * (b.target - a.target);
  c.distance = a.distance * std::pow(b.distance / a.distance, s);
  const auto pi = std::numbers::pi_v<float>;
  const float turn = std::remainder(b.yaw - a.yaw, 2.0f * pi);
  c.yaw = a.yaw + s * turn;
  c.pitch = a.pitch + s * (b.pitch - a.pitch);
  c.fovY = a.fovY + s * (b.fovY - a.fovY);
  return c;
}

}  // namespace

LiveCamera::LiveCamera(const OrbitCamera& base, bool follow, float aspect)
    : base_(base), follow_(follow), aspect_(aspect), framing_(framingFor(aspect)), shown_(base) {}

OrbitCamera LiveCamera::update(const State& film, const WandState& wands, float dt, OrbitCamera& user, bool userMoved) {
  bool empty = true;
  for (size_t i = 0; i < film.size() && empty; ++i) empty = film.alive[i] == 0;
  if (empty) {  // the tips, and 0.8 m below them: a new film's size
    const Vec3 hang(0.0f, -0.8f, 0.0f);
    stand_.resize(4);
    for (const auto& [k, p] :
         {std::pair{0, wands.leftPosition}, std::pair{1, wands.rightPosition},
          std::pair{2, Vec3(wands.leftPosition + hang)}, std::pair{3, Vec3(wands.rightPosition + hang)}})
      stand_.position.set(static_cast<size_t>(k), p);
  }
  // The framing eases every frame, shown or not, so that Home returns to where the film is now.
  const OrbitCamera followed = follow_ ? framing_.update(base_, empty ? stand_ : film, dt) : base_;
  if (userMoved) {
    user_ = true;
    sinceHome_ = kHandBack;
  }
  if (user_) {
    shown_ = user;
    return shown_;
  }
  if (sinceHome_ < kHandBack) {
    sinceHome_ = std::min(kHandBack, sinceHome_ + std::max(dt, 0.0f));
    const float u = sinceHome_ / kHandBack;
    shown_ = blend(handedBack_, followed, u * u * (3.0f - 2.0f * u));
  } else {
    shown_ = followed;
  }
  user = shown_;
  return shown_;
}

void LiveCamera::home() {
  if (!user_) return;
  user_ = false;
  handedBack_ = shown_;
  sinceHome_ = 0.0f;
}

void LiveCamera::setAspect(float aspect) {
  if (aspect == aspect_) return;
  aspect_ = aspect;
  framing_ = framingFor(aspect);
}

Eigen::Vector2f pictureCoordinates(const OrbitCamera& camera, float aspect, const Vec3& point) {
  const Eigen::Vector4f clip = camera.viewProjection(aspect) * Eigen::Vector4f(point.x(), point.y(), point.z(), 1.0f);
  if (!(clip.w() > 0.0f)) return Eigen::Vector2f::Constant(NAN);
  return {clip.x() / clip.w(), clip.y() / clip.w()};
}

}  // namespace gb
