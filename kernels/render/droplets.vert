#version 450
#extension GL_GOOGLE_include_directive : require
// Aerosol droplets as point sprites sized by their distance.
#include "render_common.glsl"
layout(std430, set = 0, binding = GB_RENDER_DROPLETS) readonly buffer DropletBuffer { vec4 droplets[]; };
layout(location = 0) out float opacity;
void main() {
  const vec4 d = droplets[gl_VertexIndex];
  opacity = d.w;
  gl_Position = u.viewProjection * vec4(d.xyz, 1.0);
  gl_PointSize = clamp(u.pointScale * u.dropletRadius / max(gl_Position.w, 1e-3), 1.5, 8.0);
}
