#version 450
#extension GL_GOOGLE_include_directive : require
// A droplet, drawn with the film into the transparency targets: a tiny water sphere is mostly clear, seen as
// a faint disc with a bright rim where it reflects the sky; it fades with age.
#include "render_common.glsl"
layout(location = 0) in float opacity;
layout(location = 0) out vec4 accum;
layout(location = 1) out float reveal;
void main() {
  const vec2 p = gl_PointCoord * 2.0 - 1.0;
  const float r2 = dot(p, p);
  if (r2 > 1.0 || opacity <= 0.0) discard;
  const float alpha = opacity * (0.15 + 0.5 * r2 * r2);  // clear in the middle, reflecting at the rim
  const vec3 c = u.skyIrradiance.rgb + vec3(0.4);
  accum = vec4(alpha * c, alpha);
  reveal = -log(max(1.0 - alpha, 1e-4));
}
