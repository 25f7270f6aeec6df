#version 450
#extension GL_GOOGLE_include_directive : require
// Diffuse props lit by the environment (sky above, ground below, as a two-colour irradiance) and the key
// light, plus a faint glossy reflection of the environment. The floor is a checkerboard of 0.5 m tiles.
#include "render_common.glsl"
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec4 albedo;
layout(location = 0) out vec4 colour;
void main() {
  const vec3 n = normalize(worldNormal);
  vec3 base = albedo.rgb;
  if (int(albedo.w + 0.5) == GB_MATERIAL_FLOOR) {
    const ivec2 tile = ivec2(floor(worldPosition.xz / 0.5));
    base *= ((tile.x + tile.y) & 1) == 0 ? 1.0 : 0.6;
  }
  const vec3 ambient = mix(environment(vec3(0.0, -1.0, 0.0)), environment(vec3(0.0, 1.0, 0.0)), 0.5 + 0.5 * n.y);
  const vec3 v = normalize(u.cameraPosition.xyz - worldPosition);
  const float key = max(dot(n, u.keyLight.xyz), 0.0);
  const vec3 gloss = 0.04 * environment(reflect(-v, n));
  colour = vec4(base * (0.6 * ambient + 1.2 * key) + gloss, 1.0);
}
