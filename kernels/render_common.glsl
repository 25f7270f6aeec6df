// Declarations the render shaders share: the uniform block, the scene's buffers, the environment lookup.
#include "render_shared.h"

layout(std430, set = 0, binding = GB_RENDER_UNIFORMS) readonly buffer UniformsBuffer { RenderUniforms u; };
layout(set = 0, binding = GB_RENDER_ENVIRONMENT) uniform sampler2D environmentMap;

const float PI = 3.14159265358979;

// Radiance arriving from direction d (world, unit; y up) out of the equirectangular environment.
vec3 environment(vec3 d) {
  const vec2 uv = vec2(0.5 + atan(d.x, -d.z) / (2.0 * PI), acos(clamp(d.y, -1.0, 1.0)) / PI);
  return textureLod(environmentMap, uv, 0.0).rgb;
}
