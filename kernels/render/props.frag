#version 450
#extension GL_GOOGLE_include_directive : require
// Diffuse props lit by the environment (the mean radiance above and below the horizon, blended by the normal)
// and the key light. The wands and string also reflect the environment faintly; a hole's rim, being water,
// reflects it strongly (a Fresnel-like rise towards grazing). The ground is plain and has no reflection (it
// covers half the picture, and a lookup per pixel is what lavapipe pays for); with distance it fades into the
// radiance just below the horizon over the environment's haze distance (5 km of clear air for the default sky,
// whose ground is painted as this floor is lit; 25 m for other images, to hide the floor's edge).
#include "render_common.glsl"
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec4 albedo;
layout(location = 0) out vec4 colour;
void main() {
  const vec3 n = normalize(worldNormal);
  const int material = int(albedo.w + 0.5);
  const vec3 ambient = mix(u.groundIrradiance.rgb, u.skyIrradiance.rgb, 0.5 + 0.5 * n.y);
  const float key = max(dot(n, u.keyLight.xyz), 0.0);
  vec3 c = albedo.rgb * (ambient + u.keyLight.w * key);
  const vec3 toPoint = worldPosition - u.cameraPosition.xyz;
  if (material == GB_MATERIAL_FLOOR) {
    c = mix(u.horizon.rgb, c, exp(-length(toPoint) / u.horizon.w));
  } else {
    const vec3 view = normalize(toPoint);
    const float grazing = pow(1.0 - abs(dot(view, n)), 3.0);
    const float shine = material == GB_MATERIAL_RIM ? 0.5 + 0.5 * grazing : 0.04;
    c = mix(c, environment(reflect(view, n)), shine);
  }
  colour = vec4(c, 1.0);
}
