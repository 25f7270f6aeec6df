#version 450
#extension GL_GOOGLE_include_directive : require
// Diffuse props lit by the environment (the mean radiance above and below the horizon, blended by the normal)
// and the key light; the wands and string also reflect the environment faintly. The floor is a checkerboard of
// 0.5 m tiles with no reflection: it covers half the picture, and a lookup per pixel is what lavapipe pays for.
#include "render_common.glsl"
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec4 albedo;
layout(location = 0) out vec4 colour;
void main() {
  const vec3 n = normalize(worldNormal);
  vec3 base = albedo.rgb;
  const bool floorTile = int(albedo.w + 0.5) == GB_MATERIAL_FLOOR;
  if (floorTile) {
    const ivec2 tile = ivec2(floor(worldPosition.xz / 0.5));
    base *= ((tile.x + tile.y) & 1) == 0 ? 1.0 : 0.6;
  }
  const vec3 ambient = mix(u.groundIrradiance.rgb, u.skyIrradiance.rgb, 0.5 + 0.5 * n.y);
  const float key = max(dot(n, u.keyLight.xyz), 0.0);
  vec3 c = base * (ambient + 0.8 * key);
  if (!floorTile) c += 0.04 * environment(reflect(normalize(worldPosition - u.cameraPosition.xyz), n));
  colour = vec4(c, 1.0);
}
