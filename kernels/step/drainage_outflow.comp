#version 450
// drainageOutflow (cpu-reference/stages/stages.cpp): drainage pass 1, the liquid particle i sends downhill
// (Eqs. 14-15) and the sum of its d_dir.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const vec3 g = vec3(params.gravityX, params.gravityY, params.gravityZ), xi = LOAD3(position, i);
  float weight = 0.0;
  for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k)
    weight += drainageDirection(xi, LOAD3(position, springNeighbour[k]), g);
  DRAIN_WEIGHT(i) = weight;
  DRAIN_OUTFLOW(i) =
      liquid[i] * min(1.0, steps[pc.stepIndex].drainageDt * params.drainageRate * weight / params.sticky);
}
