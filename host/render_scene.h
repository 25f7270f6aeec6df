#pragma once
// What the renderer draws, built on the CPU: the camera, the opaque props (floor, wands, string) as a
// triangle soup, the droplets, and the environment (the built-in studio or a user's equirectangular image).
// Pure C++ and Eigen; host/renderer.cpp uploads it.

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "bursting.h"
#include "wire_frame.h"

namespace gb {

// An orbiting camera looking at `target` (the live window's mouse turns and zooms it).
struct OrbitCamera {
  Vec3 target = Vec3(0.0f, 1.2f, 0.0f);  // point looked at (m); the default film hangs around here
  float distance = 3.2f;                 // from the target (m)
  float yaw = 0.0f;                      // about the vertical, radians; 0 looks along -z (the front)
  float pitch = 0.12f;                   // above the horizontal, radians
  float fovY = 0.75f;                    // vertical field of view, radians

  [[nodiscard]] Vec3 position() const;
  // World -> Vulkan clip space (y down, depth 0 at near .. 1 at far), for an image of this aspect ratio.
  [[nodiscard]] Eigen::Matrix4f viewProjection(float aspect) const;
};

// Floats per vertex of the props mesh: position, normal, albedo, material, padding (GB_RENDER_MESH).
inline constexpr int kPropsVertexFloats = 12;

// The floor (y = 0), and when `frame` is given the two wands (sticks held below the tips) and the string loop
// (or the ring and its handle) as tubes, as a triangle soup of kPropsVertexFloats floats per vertex.
std::vector<float> buildProps(const WireFrame* frame);

// The droplets as (x, y, z, opacity): opacity fades over the last third of a droplet's life.
std::vector<float> packDroplets(const Aerosol& aerosol, float lifetime);

// An equirectangular environment: linear RGB radiance, width x height (2:1), row 0 at the zenith.
struct EnvironmentImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;
};

// Mean radiance of the environment over the upper (y > 0) and lower hemisphere, solid-angle weighted.
std::array<Vec3, 2> hemisphereMeans(const EnvironmentImage& environment);

// The built-in studio: a grey-blue room, bright above, dark floor below the horizon, two large softboxes and
// a strip light that the film reflects as coloured highlights.
EnvironmentImage studioEnvironment(int width = 512);

}  // namespace gb
