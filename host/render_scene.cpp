#include "render_scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "render_shared.h"

namespace gb {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

void addVertex(std::vector<float>& mesh, const Vec3& p, const Vec3& n, const Vec3& albedo, int material) {
  mesh.insert(mesh.end(), {p.x(), p.y(), p.z(), n.x(), n.y(), n.z(), albedo.x(), albedo.y(), albedo.z(),
                           static_cast<float>(material), 0.0f, 0.0f});
}

// A tube of `radius` along a polyline, six sides, flat ends left open (they are never seen end-on for long).
void addTube(std::vector<float>& mesh, const std::vector<Vec3>& path, float radius, const Vec3& albedo) {
  constexpr int sides = 6;
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const Vec3 axis = (path[k + 1] - path[k]).normalized();
    const Vec3 side = (std::abs(axis.y()) < 0.9f ? axis.cross(Vec3::UnitY()) : axis.cross(Vec3::UnitX())).normalized();
    const Vec3 up = axis.cross(side);
    for (int s = 0; s < sides; ++s) {
      const float a0 = 2 * kPi * static_cast<float>(s) / sides, a1 = 2 * kPi * static_cast<float>(s + 1) / sides;
      const Vec3 n0 = std::cos(a0) * side + std::sin(a0) * up, n1 = std::cos(a1) * side + std::sin(a1) * up;
      const Vec3 quad[4][2] = {{path[k] + radius * n0, n0}, {path[k] + radius * n1, n1},
                               {path[k + 1] + radius * n1, n1}, {path[k + 1] + radius * n0, n0}};
      for (int corner : {0, 1, 2, 0, 2, 3}) addVertex(mesh, quad[corner][0], quad[corner][1], albedo, GB_MATERIAL_PLAIN);
    }
  }
}

void addFloor(std::vector<float>& mesh) {
  constexpr float half = 12.0f;
  const Vec3 corners[4] = {{-half, 0, -half}, {half, 0, -half}, {half, 0, half}, {-half, 0, half}};
  for (int corner : {0, 2, 1, 0, 3, 2}) addVertex(mesh, corners[corner], Vec3::UnitY(), Vec3(0.36f, 0.36f, 0.38f), GB_MATERIAL_FLOOR);
}

// A wand: a stick from the tip down and outwards, where a hand holds it.
void addStick(std::vector<float>& mesh, const Vec3& tip, const Vec3& outward) {
  const Vec3 handle = tip + 0.5f * (0.35f * outward - Vec3::UnitY()).normalized();
  addTube(mesh, {tip, handle}, 0.012f, Vec3(0.45f, 0.3f, 0.18f));
}

}  // namespace

Vec3 OrbitCamera::position() const {
  const Vec3 back(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
  return target + distance * back;
}

Eigen::Matrix4f OrbitCamera::viewProjection(float aspect) const {
  const Vec3 eye = position();
  const Vec3 f = (target - eye).normalized();
  const Vec3 s = f.cross(Vec3::UnitY()).normalized();
  const Vec3 up = s.cross(f);
  Eigen::Matrix4f view = Eigen::Matrix4f::Identity();
  view.row(0) << s.x(), s.y(), s.z(), -s.dot(eye);
  view.row(1) << up.x(), up.y(), up.z(), -up.dot(eye);
  view.row(2) << -f.x(), -f.y(), -f.z(), f.dot(eye);
  const float nearPlane = 0.05f, farPlane = 100.0f;
  const float t = 1.0f / std::tan(0.5f * fovY);
  Eigen::Matrix4f proj = Eigen::Matrix4f::Zero();
  proj(0, 0) = t / aspect;
  proj(1, 1) = -t;  // Vulkan's clip space has y pointing down
  proj(2, 2) = farPlane / (nearPlane - farPlane);
  proj(2, 3) = nearPlane * farPlane / (nearPlane - farPlane);
  proj(3, 2) = -1.0f;
  return proj * view;
}

std::vector<float> buildProps(const WireFrame* frame) {
  std::vector<float> mesh;
  addFloor(mesh);
  if (!frame) return mesh;
  std::vector<Vec3> loop;
  constexpr int segments = 96;
  for (int k = 0; k <= segments; ++k)
    loop.push_back(framePoint(*frame, frame->parameterEnd() * static_cast<float>(k) / segments));
  if (frame->kind == ToolKind::TwoWands) {
    addTube(mesh, loop, 0.004f, Vec3(0.85f, 0.85f, 0.8f));
    addStick(mesh, framePoint(*frame, 0.0f), -frame->axis);
    addStick(mesh, framePoint(*frame, 1.0f), frame->axis);
  } else {
    addTube(mesh, loop, 0.008f, Vec3(0.7f, 0.7f, 0.75f));
    const Vec3 bottom = frame->center + frame->depth * frame->down;
    addTube(mesh, {bottom, bottom + 0.45f * frame->down}, 0.015f, Vec3(0.45f, 0.3f, 0.18f));
  }
  return mesh;
}

std::vector<float> packDroplets(const Aerosol& aerosol, float lifetime) {
  std::vector<float> out;
  out.reserve(4 * aerosol.size());
  for (size_t i = 0; i < aerosol.size(); ++i) {
    const float left = 1.0f - aerosol.age[i] / std::max(lifetime, 1e-6f);
    out.insert(out.end(), {aerosol.position.x[i], aerosol.position.y[i], aerosol.position.z[i], std::clamp(3.0f * left, 0.0f, 1.0f)});
  }
  return out;
}

std::array<Vec3, 2> hemisphereMeans(const EnvironmentImage& env) {
  std::array<Eigen::Vector3d, 2> sum{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<double, 2> weight{0, 0};
  for (int row = 0; row < env.height; ++row) {
    const double polar = std::numbers::pi * (row + 0.5) / env.height;
    const size_t half = polar < 0.5 * std::numbers::pi ? 0 : 1;
    const double w = std::sin(polar);  // solid angle of a texel of this row
    for (int col = 0; col < env.width; ++col) {
      const float* c = &env.rgb[3 * (static_cast<size_t>(row) * env.width + col)];
      sum[half] += w * Eigen::Vector3d(c[0], c[1], c[2]);
      weight[half] += w;
    }
  }
  return {(sum[0] / std::max(weight[0], 1e-12)).cast<float>(), (sum[1] / std::max(weight[1], 1e-12)).cast<float>()};
}

EnvironmentImage studioEnvironment(int width) {
  EnvironmentImage env;
  env.width = width;
  env.height = width / 2;
  env.rgb.resize(static_cast<size_t>(env.width) * env.height * 3);
  // Softboxes: direction (unit), angular half-size (radians), radiance.
  struct Light {
    Vec3 direction;
    float halfSize;
    Vec3 radiance;
  };
  const Light lights[] = {{Vec3(-0.6f, 0.5f, 0.62f).normalized(), 0.42f, Vec3(7.0f, 6.8f, 6.4f)},
                          {Vec3(0.7f, 0.3f, 0.65f).normalized(), 0.34f, Vec3(5.0f, 5.3f, 6.0f)},
                          {Vec3(0.0f, 0.95f, 0.3f).normalized(), 0.16f, Vec3(10.0f, 10.0f, 10.0f)}};
  for (int row = 0; row < env.height; ++row) {
    const float polar = kPi * (static_cast<float>(row) + 0.5f) / static_cast<float>(env.height);
    for (int col = 0; col < env.width; ++col) {
      // Same parameterisation as environment() in kernels/render_common.glsl: u = 0.5 + atan(x, -z) / 2 pi.
      const float azimuth = 2 * kPi * ((static_cast<float>(col) + 0.5f) / static_cast<float>(env.width) - 0.5f);
      const Vec3 d(std::sin(polar) * std::sin(azimuth), std::cos(polar), -std::sin(polar) * std::cos(azimuth));
      // A dark backdrop ahead (-z), as photographers shoot bubbles, lighter walls behind the camera, a dim floor.
      const float behindCamera = std::clamp(0.5f + 0.5f * d.z(), 0.0f, 1.0f);
      const Vec3 wall = Vec3(0.05f, 0.06f, 0.08f) + behindCamera * Vec3(0.35f, 0.37f, 0.40f);
      Vec3 c = d.y() > 0 ? wall * (0.8f + 0.4f * d.y()) : Vec3(0.10f, 0.09f, 0.085f) * (1.0f + d.y());
      for (const Light& l : lights) {
        const float angle = std::acos(std::clamp(d.dot(l.direction), -1.0f, 1.0f));
        c += l.radiance * std::clamp((l.halfSize - angle) / (0.15f * l.halfSize), 0.0f, 1.0f);  // soft edge
      }
      float* out = &env.rgb[3 * (static_cast<size_t>(row) * env.width + col)];
      out[0] = c.x();
      out[1] = c.y();
      out[2] = c.z();
    }
  }
  return env;
}

}  // namespace gb
