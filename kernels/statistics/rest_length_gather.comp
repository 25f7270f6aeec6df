#version 450
// The rest lengths of a mesh whose merges renumbered its springs (makeMerges of cpu-reference/topology/film_growth.cpp,
// DeviceResidency::updateMergedRegion): each of the pc.count springs keeps the rest length of the spring of the mesh
// before that it comes from. From pc.first on in the reduce buffer: where each spring comes from (a float; negative
// for a spring made anew, whose rest length the host writes), then the rest lengths of the mesh before.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint k = gl_GlobalInvocationID.x;
  if (k >= pc.count) return;
  const float from = reduce[pc.first + k];
  if (from >= 0.0) restLength[k] = reduce[pc.first + pc.count + uint(from)];
}
