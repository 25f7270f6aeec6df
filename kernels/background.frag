#version 450
#extension GL_GOOGLE_include_directive : require
// The environment seen behind everything: a view ray per pixel, looked up in the environment map.
#include "render_common.glsl"
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 colour;
void main() {
  const vec4 far = u.inverseViewProjection * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
  colour = vec4(environment(normalize(far.xyz / far.w - u.cameraPosition.xyz)), 1.0);
}
