#include "host/camera_layer.h"

#include <cmath>

namespace gb {

Eigen::Matrix4f DepthCameraView::projection(float aspect) const {
  // A camera point (x, y, z) is seen at image pixel u = cx + fx x / z, v = cy - fy y / z. The picture is the image
  // scaled to its height: ndc_y = 2 v / imageHeight - 1, and ndc_x = side (u - imageWidth / 2) k, k = 2 / (aspect
  // imageHeight), side -1 when mirrored. Times w = z, both are linear in the point.
  const float side = mirrored ? -1.0f : 1.0f;
  const float k = 2.0f / (aspect * static_cast<float>(imageHeight));
  const float h = 2.0f / static_cast<float>(imageHeight);
  const Eigen::Vector2f depth = depthOfDistance();
  Eigen::Matrix4f p = Eigen::Matrix4f::Zero();
  p(0, 0) = side * k * fx;
  p(0, 2) = side * k * (cx - 0.5f * static_cast<float>(imageWidth));
  p(1, 1) = -h * fy;
  p(1, 2) = h * cy - 1.0f;
  p(2, 2) = depth.x();  // z_clip / w = a - b / z
  p(2, 3) = -depth.y();
  p(3, 2) = 1.0f;
  return p;
}

float DepthCameraView::scale() const { return std::cbrt(worldToCamera.topLeftCorner<3, 3>().determinant()); }

Eigen::Matrix4f DepthCameraView::skyRays(float aspect) const {
  Eigen::Matrix4f turn = Eigen::Matrix4f::Identity();
  turn.topLeftCorner<3, 3>() = worldToCamera.topLeftCorner<3, 3>() / scale();
  return (projection(aspect) * turn).inverse();
}

Vec3 DepthCameraView::eye() const {
  const Eigen::Vector4f origin = worldToCamera.inverse() * Eigen::Vector4f(0.0f, 0.0f, 0.0f, 1.0f);
  return origin.head<3>() / origin.w();
}

float DepthCameraView::pointScale(int height) const {
  return static_cast<float>(height) / static_cast<float>(imageHeight) * fy * scale();
}

Eigen::Vector4f DepthCameraView::imageOfPicture(int width, int height) const {
  const float perPixel = static_cast<float>(imageHeight) / static_cast<float>(height);  // image pixels
  const float side = mirrored ? -1.0f : 1.0f;
  return {side * perPixel, 0.5f * static_cast<float>(imageWidth) - side * perPixel * 0.5f * static_cast<float>(width),
          perPixel, 0.0f};
}

Eigen::Vector2f DepthCameraView::depthOfDistance() const {
  const float a = kFar / (kFar - kNear);
  return {a, a * kNear};
}

float DepthCameraView::clipDepth(float z) const {
  const Eigen::Vector2f d = depthOfDistance();
  return d.x() - d.y() / z;
}

}  // namespace gb
