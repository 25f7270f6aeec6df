#version 450
// filmFlowLimit (cpu-reference/stages/stages.cpp): film flow pass 2, the share of its outflow particle i can give;
// keeps its surfactant for the gathers of pass 3.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  FLOW(surfactantBeforeBlock, i) = FLOW(surfactantBlock, i);
  if (alive[i] == 0u) {
    FLOW(flowLimitBlock, i) = 0.0;
    return;
  }
  const float dt = steps[pc.stepIndex].drainageDt;
  float swept = 0.0;
  for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
    const uint j = springNeighbour[k];
    if (alive[j] == 0u) continue;
    swept += filmFlowSweptArea(dt, i, j);
  }
  const float black = params.blackFilmThickness * voronoiArea[i];  // drainage stops at black film
  const float outflow = swept * thickness[i], allowed = kLargestOutflowShare * max(liquid[i] - black, 0.0);
  FLOW(flowLimitBlock, i) = outflow > allowed ? allowed / outflow : 1.0;
}
