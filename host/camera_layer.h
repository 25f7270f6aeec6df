#pragma once
// The mirror view's camera and image: the scene seen from the depth camera itself (its intrinsics and its place in
// the world), flipped left-right as a mirror shows the performer, with what the camera saw drawn into it at its own
// depth. The renderer draws the image into the opaque pass (kernels/render/camera_image.frag), writing each pixel's
// depth, so that the depth test settles what covers what: a hand in front of the film covers it, the film in front
// of the body covers the body. Pure C++ and Eigen; app/show/mirror_view.h fills them from the calibration and the
// depth frames.

#include <Eigen/Dense>
#include <cstdint>
#include <vector>

#include "model/film.h"

namespace gb {

struct DepthCameraView {
  // World -> the depth camera's space (x right in its image, y up, z away from it; metres of camera space, which a
  // calibration may scale against the world's).
  Eigen::Matrix4f worldToCamera = Eigen::Matrix4f::Identity();
  float fx = 0.0f, fy = 0.0f, cx = 0.0f, cy = 0.0f;  // the camera image's intrinsics (pixels)
  int imageWidth = 0, imageHeight = 0;               // the camera image's size (pixels)
  bool mirrored = true;  // left and right swapped, as a mirror shows the performer facing the camera

  // The picture shows the camera image's full height at its centre, and beyond its sides as far as the aspect
  // ratio (width / height) reaches.
  // Camera space -> Vulkan clip space (y down, depth 0 near .. 1 far), for a picture of this aspect ratio.
  [[nodiscard]] Eigen::Matrix4f projection(float aspect) const;
  [[nodiscard]] Eigen::Matrix4f viewProjection(float aspect) const { return projection(aspect) * worldToCamera; }
  // Clip space -> a view ray's direction in the world (OrbitCamera::skyRays): the projection and the turn alone.
  [[nodiscard]] Eigen::Matrix4f skyRays(float aspect) const;
  [[nodiscard]] Vec3 eye() const;  // where the camera is in the world
  // Camera-space metres per world metre.
  [[nodiscard]] float scale() const;
  // Pixels per world metre at a camera-space distance of 1 (RenderUniforms::pointScale), for a picture `height` high.
  [[nodiscard]] float pointScale(int height) const;
  // The camera image's pixel of a picture's pixel: (sx, ox, sy, oy) with u = sx X + ox, v = sy Y + oy, for a
  // picture of width x height pixels (X, Y from its top left).
  [[nodiscard]] Eigen::Vector4f imageOfPicture(int width, int height) const;
  // The depth buffer's value of a point at camera-space distance z is a - b / z: (a, b).
  [[nodiscard]] Eigen::Vector2f depthOfDistance() const;
  // The same for one distance (m of camera space).
  [[nodiscard]] float clipDepth(float z) const;

  static constexpr float kNear = 0.05f, kFar = 60.0f;  // camera-space metres: the depth range drawn
};

// What the depth camera saw, in its own pixels, to draw into the mirror view.
struct CameraImage {
  int width = 0, height = 0;
  std::vector<uint32_t> rgba;  // per pixel, sRGB, packed R | G << 8 | B << 16 | A << 24
  std::vector<float> depth;    // camera-space distance z (m) of each pixel; 0: nothing drawn there
};

}  // namespace gb
