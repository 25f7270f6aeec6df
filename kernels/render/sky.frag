#version 450
#extension GL_GOOGLE_include_directive : require
// The environment seen behind everything, along each pixel's view ray, into the sky image that the resolve reads
// (composite.frag). The sky is at infinity: it changes only when the view turns or zooms, not when the camera
// moves, so the renderer draws it again only then (Renderer: SkyView). On lavapipe its lookup per pixel cost the
// resolve a seventh of a frame.
#include "render_common.glsl"
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 colour;

void main() {
  const vec4 far = u.skyRays * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
  colour = vec4(environment(normalize(far.xyz / far.w)), 1.0);
}
