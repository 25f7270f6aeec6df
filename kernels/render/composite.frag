#version 450
#extension GL_GOOGLE_include_directive : require
// Resolves the transparent film over the opaque scene (weighted blended OIT) and encodes for display:
// exposure and a soft shoulder so bright reflections do not clip hard, into an sRGB target. Where no
// prop covers the pixel (alpha < 1: none, or part of it at an anti-aliased edge) the sky shows through the rest:
// read from the sky image (sky.frag), which is drawn again only when the view turns.
#include "render_common.glsl"
layout(set = 1, binding = GB_COMPOSITE_OPAQUE) uniform sampler2D opaqueImage;
layout(set = 1, binding = GB_COMPOSITE_ACCUM) uniform sampler2D accumImage;
layout(set = 1, binding = GB_COMPOSITE_REVEAL) uniform sampler2D revealImage;
layout(set = 1, binding = GB_COMPOSITE_SKY) uniform sampler2D skyImage;
layout(location = 0) out vec4 colour;

void main() {
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const vec4 opaque = texelFetch(opaqueImage, p, 0);  // premultiplied: cleared to 0, props write alpha 1
  vec3 behind = opaque.rgb;
  if (opaque.a < 0.999) behind += (1.0 - opaque.a) * texelFetch(skyImage, p, 0).rgb;
  const vec4 a = texelFetch(accumImage, p, 0);
  const float through = exp(-texelFetch(revealImage, p, 0).r);  // product of (1 - alpha) over the sheets
  const vec3 film = a.rgb / max(a.a, 1e-5);                     // weighted mean of the sheets' colour / alpha
  const vec3 radiance = u.exposure * (film * (1.0 - through) + behind * through);
  const vec3 shoulder = radiance / (1.0 + max(radiance - 0.8, 0.0));  // identity below 0.8
  colour = vec4(clamp(shoulder, 0.0, 1.0), 1.0);                      // the sRGB target encodes on store
}
