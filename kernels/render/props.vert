#version 450
#extension GL_GOOGLE_include_directive : require
// Opaque props (floor, wands, string, hole rims), pulled from a storage buffer of 12 floats per vertex. A tube
// thinner than u.minTubePixels on screen is widened to it about its axis (the vertex less radius times its
// normal), so that the string stays a continuous line that multisampling can smooth instead of a row of dashes.
#include "render_common.glsl"
layout(std430, set = 0, binding = GB_RENDER_MESH) readonly buffer MeshBuffer { float mesh[]; };
layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec4 albedo;  // w: material
void main() {
  const int v = 12 * gl_VertexIndex;
  worldPosition = vec3(mesh[v], mesh[v + 1], mesh[v + 2]);
  worldNormal = vec3(mesh[v + 3], mesh[v + 4], mesh[v + 5]);
  albedo = vec4(mesh[v + 6], mesh[v + 7], mesh[v + 8], mesh[v + 9]);
  const float radius = mesh[v + 10];
  if (radius > 0.0) {
    const vec3 axis = worldPosition - radius * worldNormal;
    const float distance = max((u.viewProjection * vec4(axis, 1.0)).w, 1e-3);
    const float wanted = u.minTubePixels * distance / u.pointScale;  // metres per pixel there, times the width
    worldPosition = axis + max(radius, wanted) * worldNormal;
  }
  gl_Position = u.viewProjection * vec4(worldPosition, 1.0);
}
