#version 450
// computeVertexGeometry (cpu-reference/stages.cpp): unit vertex normal and mixed Voronoi area of particle i
// from its CSR triangles (Meyer et al. 2003).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

float mixedVoronoiCorner(vec3 xi, vec3 xj, vec3 xk, float area) {
  if (area <= 0.0) return 0.0;
  const vec3 eij = xj - xi, eik = xk - xi, ejk = xk - xj;
  const float dotI = dot(eij, eik), dotJ = -dot(eij, ejk), dotK = dot(eik, ejk);
  if (dotI < 0.0) return 0.5 * area;
  if (dotJ < 0.0 || dotK < 0.0) return 0.25 * area;
  return (dot(eij, eij) * dotK + dot(eik, eik) * dotJ) / (16.0 * area);
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  vec3 normalSum = vec3(0.0);
  float area = 0.0;
  for (uint k = triangleOffset[i]; k < triangleOffset[i + 1u]; ++k) {
    const uint t = triangleIndex[k];
    const uint c = triangles[3u * t] == i ? 0u : (triangles[3u * t + 1u] == i ? 1u : 2u);
    const vec3 xi = LOAD3(position, triangles[3u * t + c]);
    const vec3 xj = LOAD3(position, triangles[3u * t + (c + 1u) % 3u]);
    const vec3 xk = LOAD3(position, triangles[3u * t + (c + 2u) % 3u]);
    const vec3 doubleAreaNormal = cross(xj - xi, xk - xi);
    normalSum += doubleAreaNormal;
    area += mixedVoronoiCorner(xi, xj, xk, 0.5 * length(doubleAreaNormal));
  }
  const float len = length(normalSum);
  STORE3(normal, i, len > 0.0 ? normalSum / len : vec3(0.0));
  voronoiArea[i] = area;
}
