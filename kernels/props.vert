#version 450
#extension GL_GOOGLE_include_directive : require
// Opaque props (floor, wands, string), pulled from a storage buffer of 12 floats per vertex.
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
  gl_Position = u.viewProjection * vec4(worldPosition, 1.0);
}
