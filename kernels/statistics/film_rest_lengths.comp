#version 450
// The rest-length rules between steps, on the device, from the state as the last step left it: with GB_RULE_YIELD
// the plastic yield (yieldStretchedSprings of cpu-reference/topology/film_growth.cpp: every living spring off the wire
// stretched past yieldStretch times its rest length, both ends at least yieldThickness thick, rests where it stays at
// the yield stretch), with GB_RULE_PAYOUT the wire's payout (payOutFilmAtWire: every rung stretched past
// growthStretch rests as new film, prestrained at its length), with GB_RULE_CONTRACT the contraction of a closed
// film's slack springs (contractSlackSprings: every living spring off the wire that is slack with both ends thinner
// than the dip goes PushBlock::ruleShare of the way to its taut rest length). Each spring is changed by its
// lower-numbered end (the CPU's springEnds order).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count || alive[i] == 0u) return;
  const bool yield = (pc.reduceFlags & GB_RULE_YIELD) != 0u, payout = (pc.reduceFlags & GB_RULE_PAYOUT) != 0u;
  const bool contract = (pc.reduceFlags & GB_RULE_CONTRACT) != 0u;
  const float dipThickness = initialThicknessOf(params.areaWeight);
  const bool wireI = boundary[i] != 0u;
  const vec3 x = LOAD3(position, i);
  for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
    const uint j = springNeighbour[k];
    if (j < i || alive[j] == 0u) continue;
    const bool wireJ = boundary[j] != 0u;
    const float len = length(x - LOAD3(position, j));
    const uint spring = springIndex[k];
    if (yield && !wireI && !wireJ &&
        springYields(len, restLength[spring], min(thickness[i], thickness[j]), params.yieldStretch,
                     params.yieldThickness))
      restLength[spring] = len / params.yieldStretch;
    if (payout && wireI != wireJ && rungPaysOut(len, restLength[spring], params.growthStretch))
      restLength[spring] = len * (1.0 - params.springPrestrain);
    const float rest = restLength[spring];
    if (contract && !wireI && !wireJ && springContracts(len, rest, max(thickness[i], thickness[j]), dipThickness)) {
      const float taut = tautRestLengthOf(len, rest, params.springPrestrain, params.energyNeutralContraction);
      restLength[spring] = contractedRestLengthOf(rest, taut, pc.ruleShare);
    }
  }
}
