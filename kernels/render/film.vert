#version 450
#extension GL_GOOGLE_include_directive : require
// The film, pulled straight from the simulation's structure-of-arrays buffers (the Vulkan stepper's own, or
// the renderer's copy of the CPU state). An indexed draw whose index buffer is the film's triangles: vertex k is
// particle k.
#include "render_common.glsl"
layout(std430, set = 0, binding = GB_RENDER_POSITION) readonly buffer PositionBuffer { float position[]; };
layout(std430, set = 0, binding = GB_RENDER_NORMAL) readonly buffer NormalBuffer { float normal[]; };
layout(std430, set = 0, binding = GB_RENDER_THICKNESS) readonly buffer ThicknessBuffer { float thickness[]; };
layout(std430, set = 0, binding = GB_RENDER_AIR_FLOW) readonly buffer AirFlowBuffer { float airFlow[]; };
layout(std430, set = 0, binding = GB_RENDER_VARIATION) readonly buffer VariationBuffer { float variation[]; };
layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out float filmThickness;
layout(location = 3) out float airFlowStrength;

vec3 load3(uint i, uint n, bool isNormal) {
  return isNormal ? vec3(normal[i], normal[n + i], normal[2 * n + i])
                  : vec3(position[i], position[n + i], position[2 * n + i]);
}

void main() {
  const uint i = gl_VertexIndex;
  const uint n = u.particles;
  worldPosition = load3(i, n, false);
  worldNormal = load3(i, n, true);
  // The drawn swirls (host/film_swirls.h) multiply the simulated thickness, which is their mean.
  filmThickness = thickness[i] * (u.thicknessVariation != 0u ? variation[i] : 1.0);
  airFlowStrength = length(vec3(airFlow[i], airFlow[n + i], airFlow[2 * n + i]));
  gl_Position = u.viewProjection * vec4(worldPosition, 1.0);
}
