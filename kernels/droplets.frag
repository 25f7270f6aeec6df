#version 450
#extension GL_GOOGLE_include_directive : require
// A round droplet: water reflects the sky at its rim, so it is drawn as a bright bead, fading with age.
#include "render_common.glsl"
layout(location = 0) in float opacity;
layout(location = 0) out vec4 colour;
void main() {
  const vec2 p = gl_PointCoord * 2.0 - 1.0;
  const float r2 = dot(p, p);
  if (r2 > 1.0 || opacity <= 0.0) discard;
  colour = vec4(opacity * (0.4 + 0.6 * r2) * (u.skyIrradiance.rgb + vec3(0.3)), 1.0);
}
