#version 450
#extension GL_GOOGLE_include_directive : require
// The film's two sides, transparent, into the weighted blended order-independent transparency targets
// (McGuire and Bavoil 2013): every sheet of a folded film adds its weighted premultiplied colour to `accum`
// and its optical depth -log(1 - alpha) to `reveal`, whatever the drawing order.
//
// Interference colouring: the film reflects R(e, theta) of the environment in the mirror direction (R from the
// spectral lookup table, per colour channel) and transmits the rest of what is behind it. A film micrometres
// thick displaces what is seen through it by less than its thickness (a parallel plate), so the transmitted
// image is not shifted: refraction shows as the (1 - R) dimming of the background, strongest at grazing angles.
#include "colour_maps.h"
#include "render_common.glsl"
#include "thin_film_lut.h"
layout(set = 0, binding = GB_RENDER_LUT) uniform sampler2D thinFilmLut;
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in float filmThickness;
layout(location = 3) in float airFlowStrength;
layout(location = 0) out vec4 accum;
layout(location = 1) out float reveal;

// The sheet's reflected radiance (premultiplied) and its opacity. The thickness is the simulated one interpolated
// across the triangle. Black film (thinner than u.blackFilmThickness) is tens of nanometres thick and reflects
// almost nothing: it is drawn as a film of no thickness, whose two reflections cancel, so the patch shows dark and
// clear, with an edge finer than the particles.
vec4 interference(vec3 n, vec3 v) {
  const float cosTheta = clamp(dot(n, v), 0.0, 1.0);
  const float e = filmThickness < u.blackFilmThickness ? 0.0 : filmThickness;
  const vec4 r = texture(thinFilmLut, vec2(lutThicknessTexture(e), lutAngleTexture(cosTheta)));
  return vec4(r.rgb * environment(reflect(-v, n)), r.a);
}

// A diagnostic colour map drawn as a mostly opaque sheet, shaded a little so folds stay readable.
vec4 diagnostic(vec3 n, vec3 v) {
  vec3 c;
  if (u.colouring == GB_COLOURING_THICKNESS) {
    const float t = filmThickness / u.thickColour;
    c = vec3(thicknessRed(t), thicknessGreen(t), thicknessBlue(t));
  } else {
    const float t = clamp(airFlowStrength / u.airFlowColour, 0.0, 1.0);
    c = vec3(airFlowRed(t), airFlowGreen(t), airFlowBlue(t));
  }
  const float alpha = 0.75;
  return vec4(alpha * c * (0.55 + 0.45 * abs(dot(n, v))), alpha);
}

void main() {
  const vec3 v = normalize(u.cameraPosition.xyz - worldPosition);
  vec3 n = normalize(worldNormal);
  if (dot(n, v) < 0.0) n = -n;  // two-sided: the side facing the viewer
  const vec4 c = u.colouring == GB_COLOURING_INTERFERENCE ? interference(n, v) : diagnostic(n, v);
  // Distance weight of McGuire and Bavoil's Eq. (7), distances in metres: where sheets overlap, the nearer
  // one's colour counts more in the mean; the transmitted light is exact whatever the weight.
  const float d = length(u.cameraPosition.xyz - worldPosition);
  const float w = clamp(10.0 / (1e-5 + pow(d / 5.0, 2.0) + pow(d / 200.0, 6.0)), 1e-2, 3e3);
  accum = vec4(c.rgb, c.a) * w;
  reveal = -log(max(1.0 - c.a, 1e-4));
}
