#version 450
// drainageGather (cpu-reference/stages/stages.cpp): drainage pass 2, Eq. (15) as a gather; conserves liquid.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint j = gl_GlobalInvocationID.x;
  if (j >= pc.count) return;
  const vec3 g = vec3(params.gravityX, params.gravityY, params.gravityZ), xj = LOAD3(position, j);
  float received = 0.0;
  for (uint k = springOffset[j]; k < springOffset[j + 1u]; ++k) {
    const uint i = springNeighbour[k];
    if (DRAIN_WEIGHT(i) > 0.0)
      received += DRAIN_OUTFLOW(i) * drainageDirection(LOAD3(position, i), xj, g) / DRAIN_WEIGHT(i);
  }
  liquid[j] = liquid[j] - DRAIN_OUTFLOW(j) + received;
}
