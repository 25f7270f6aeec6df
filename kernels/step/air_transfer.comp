#version 450
// airTransfer (cpu-reference/stages/stages.cpp): Eqs. (7)-(8) / Algorithm 2 as a Jacobi gather from airFlow
// (front) into airFlowNext (back); the host swaps the two bindings after the dispatch.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (boundary[i] != 0u || params.airTransfer == 0) {  // Algorithm 2, line 2: the end particles take the new inflow
    STORE3(airFlowNext, i, LOAD3(airInflow, i));
    return;
  }
  const vec3 xi = LOAD3(position, i);
  vec3 weighted = vec3(0.0);
  float weightSum = 0.0;
  for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
    const uint j = springNeighbour[k];
    const vec3 airJ = LOAD3(airFlow, j);
    if (airJ == vec3(0.0)) continue;  // sends nothing (a free bubble's air everywhere): no square roots spent
    const vec3 toI = xi - LOAD3(position, j);
    const float norms = length(toI) * length(airJ);
    if (norms <= 0.0) continue;
    const float aDir = max(dot(toI, airJ) / norms, 0.0);  // Eq. (7), seen from the sender j
    if (aDir <= params.airDirectionThreshold) continue;
    weighted += aDir * airJ;
    weightSum += aDir;
  }
  STORE3(airFlowNext, i, weightSum > 0.0 ? weighted / weightSum : vec3(0.0));  // Eq. (8)
}
