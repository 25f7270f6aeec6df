#version 450
// filmFlowGather (cpu-reference/stages/stages.cpp): film flow pass 3, particle j's liquid and surfactant after its
// edges' fluxes, each the exact negative of its neighbour's (the flow conserves liquid), less what evaporated. Each
// edge's two swept areas are computed here again, where the CPU keeps them from pass 2 (a value per edge, for which
// the device has no binding to spare): the same floats.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint j = gl_GlobalInvocationID.x;
  if (j >= pc.count) return;
  storeFlow3(flowVelocityBlock, j, loadFlow3(flowVelocityNextBlock, j));
  if (alive[j] == 0u) return;
  const float dt = steps[pc.stepIndex].drainageDt;
  float liquidOut = 0.0, surfactantOut = 0.0;
  for (uint k = springOffset[j]; k < springOffset[j + 1u]; ++k) {
    const uint i = springNeighbour[k];
    if (alive[i] == 0u) continue;
    const float sent = filmFlowSent(dt, j, i);
    const float received = filmFlowSent(dt, i, j);
    liquidOut += sent - received;
    surfactantOut += sent * FLOW(surfactantBeforeBlock, j) - received * FLOW(surfactantBeforeBlock, i);
  }
  const float before = FLOW(surfactantBeforeBlock, j);
  const float flowed = liquid[j] - liquidOut;
  const float newLiquid =
      flowed - evaporatedLiquid(params.evaporationRate, dt, flowed, voronoiArea[j], params.blackFilmThickness);
  const float surfactant = before * liquid[j] - surfactantOut;  // evaporation leaves it behind
  liquid[j] = newLiquid;
  FLOW(surfactantBlock, j) = newLiquid > 0.0 ? surfactant / newLiquid : before;
}
