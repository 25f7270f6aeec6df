#version 450
// triangleGeometry (cpu-reference/stages/stages.cpp), the geometry stage's first pass: triangle t's
// area-weighted normal and the mixed Voronoi area of each corner (Meyer et al. 2003).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

// mixedVoronoiCorner of cpu-reference/stages/stages.cpp.
float mixedVoronoiCorner(vec3 xi, vec3 xj, vec3 xk, float area) {
  const vec3 eij = xj - xi, eik = xk - xi, ejk = xk - xj;
  if (!(area > 1e-6 * (dot(eij, eij) + dot(eik, eik)))) return area / 3.0;
  const float dotI = dot(eij, eik), dotJ = -dot(eij, ejk), dotK = dot(eik, ejk);
  if (dotI < 0.0) return 0.5 * area;
  if (dotJ < 0.0 || dotK < 0.0) return 0.25 * area;
  return (dot(eij, eij) * dotK + dot(eik, eik) * dotJ) / (16.0 * area);
}

void main() {
  const uint t = gl_GlobalInvocationID.x;
  if (t >= pc.count) return;
  const vec3 x[3] = vec3[3](LOAD3(position, triangles[3u * t]), LOAD3(position, triangles[3u * t + 1u]),
                            LOAD3(position, triangles[3u * t + 2u]));
  const vec3 doubleAreaNormal = cross(x[1] - x[0], x[2] - x[0]);
  triangleNormal[t] = doubleAreaNormal.x;
  triangleNormal[pc.triangles + t] = doubleAreaNormal.y;
  triangleNormal[2u * pc.triangles + t] = doubleAreaNormal.z;
  const float area = 0.5 * length(doubleAreaNormal);
  for (uint c = 0u; c < 3u; ++c)
    cornerArea[3u * t + c] = mixedVoronoiCorner(x[c], x[(c + 1u) % 3u], x[(c + 2u) % 3u], area);
}
