#version 450
// vertexGeometry (cpu-reference/stages/stages.cpp), the geometry stage's second pass: unit vertex normal and
// mixed Voronoi area of particle i gathered from its CSR triangles.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  vec3 normalSum = vec3(0.0);
  float area = 0.0;
  for (uint k = triangleOffset[i]; k < triangleOffset[i + 1u]; ++k) {
    const uint corner = triangleCorner[k], t = corner / 3u;
    normalSum += vec3(triangleNormal[t], triangleNormal[pc.triangles + t], triangleNormal[2u * pc.triangles + t]);
    area += cornerArea[corner];
  }
  const float len = length(normalSum);
  STORE3(normal, i, len > 0.0 ? normalSum / len : vec3(0.0));
  voronoiArea[i] = area;
}
