#version 450
#extension GL_GOOGLE_include_directive : require
// The mirror view's camera image (host/camera_layer.h), drawn over the whole picture in the opaque pass: each
// fragment shows its pixel of the camera image where the camera saw something to draw (the performer; the room too
// when it is shown), at that pixel's own depth. The depth test against the props and then the film's pass does the
// rest: a hand in front of the film covers it, the film in front of the body covers the body.
#include "render_common.glsl"
layout(std430, set = 0, binding = GB_RENDER_CAMERA_COLOUR) readonly buffer CameraColour { uint cameraColour[]; };
layout(std430, set = 0, binding = GB_RENDER_CAMERA_DEPTH) readonly buffer CameraDepth { float cameraDepth[]; };
layout(location = 0) out vec4 colour;
void main() {
  const ivec2 size = ivec2(u.cameraDepth.zw);
  const ivec2 p = ivec2(floor(u.cameraImage.xz * gl_FragCoord.xy + u.cameraImage.yw));
  if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) discard;
  const int i = p.y * size.x + p.x;
  const float z = cameraDepth[i];
  if (z <= 0.0) discard;
  // sRGB to linear radiance by the power 2.2 (within 1% of the exact curve over the range a camera image uses).
  colour = vec4(pow(unpackUnorm4x8(cameraColour[i]).rgb, vec3(2.2)), 1.0);
  gl_FragDepth = u.cameraDepth.x - u.cameraDepth.y / z;
}
