// Declarations the render shaders share: the uniform block, the scene's buffers, the environment lookup.
#include "render_shared.h"

layout(std430, set = 0, binding = GB_RENDER_UNIFORMS) readonly buffer UniformsBuffer { RenderUniforms u; };
layout(set = 0, binding = GB_RENDER_ENVIRONMENT) uniform sampler2D environmentMap;

const float PI = 3.14159265358979;

// Polynomial atan2 and acos: lavapipe evaluates the built-ins at full precision, which costs a sixth of a frame
// when done for every pixel. Errors: 1e-5 rad (atan2, minimax polynomial in the octant), 7e-5 rad (acos,
// Abramowitz and Stegun 4.4.45): under 0.006 texel of a 512-wide environment.
float fastAtan2(float y, float x) {
  const float ax = abs(x), ay = abs(y);
  const float a = min(ax, ay) / max(max(ax, ay), 1e-20);
  const float s = a * a;
  float r = ((-0.0464964749 * s + 0.15931422) * s - 0.327622764) * s * a + a;
  if (ay > ax) r = 0.5 * PI - r;
  if (x < 0.0) r = PI - r;
  return y < 0.0 ? -r : r;
}
float fastAcos(float x) {
  const float ax = min(abs(x), 1.0);
  const float r = sqrt(1.0 - ax) * (1.5707288 + ax * (-0.2121144 + ax * (0.0742610 - 0.0187293 * ax)));
  return x < 0.0 ? PI - r : r;
}

// Radiance arriving from direction d (world, unit; y up) out of the equirectangular environment.
vec3 environment(vec3 d) {
  const vec2 uv = vec2(0.5 + fastAtan2(d.x, -d.z) / (2.0 * PI), fastAcos(d.y) / PI);
  return textureLod(environmentMap, uv, 0.0).rgb;
}
