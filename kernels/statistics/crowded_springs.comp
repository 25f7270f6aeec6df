#version 450
// What a round of merges tries (mergeCrowdedParticles of cpu-reference/topology/film_growth.cpp; CrowdedCandidates of
// device_residency.h), in one workgroup. First the median of the living springs' squared lengths (both ends alive;
// squaredLengthOf, as the CPU sums them), exactly: a radix select over their float bits, which order as non-negative
// floats do, 8 bits a pass, each pass counting the springs that share the bits chosen so far. Then every living spring
// that the film checks' loosened tests (kFilmCheckMargin, as film_statistics_terms.comp counts them) find crowded and
// shorter than kCrowdedEdge of the median spring is listed. The results from pc.first on in the reduce buffer
// (GB_CROWDED_*); pc.count is the particle count.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

const float kMore = 1.0 + kFilmCheckMargin, kLess = 1.0 - kFilmCheckMargin;
const uint kDigits = 256u;  // 8 bits a pass

shared uint histogram[kDigits];
shared uint living, chosenBits, rankLeft, listed;

float squaredSpringLength(uint i, uint j) {
  const vec3 d = LOAD3(position, i) - LOAD3(position, j);
  return squaredLengthOf(d.x, d.y, d.z);
}

// The digit of the pass at `shift` that holds the median: the springs below it in the digits before are passed over.
void chooseDigit(uint shift) {
  uint digit = 0u;
  while (digit + 1u < kDigits && histogram[digit] <= rankLeft) {
    rankLeft -= histogram[digit];
    ++digit;
  }
  chosenBits |= digit << shift;
}

void main() {
  const uint lane = gl_LocalInvocationID.x, lanes = gl_WorkGroupSize.x;
  if (lane == 0u) {
    living = 0u;
    chosenBits = 0u;
    listed = 0u;
  }
  barrier();
  uint mine = 0u;
  for (uint i = lane; i < pc.count; i += lanes) {
    if (alive[i] == 0u) continue;
    for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
      const uint j = springNeighbour[k];
      if (j > i && alive[j] != 0u) ++mine;
    }
  }
  atomicAdd(living, mine);
  barrier();
  if (lane == 0u) rankLeft = living / 2u;  // the CPU's median: the element at size / 2 of the sorted lengths
  for (int shift = 24; shift >= 0; shift -= 8) {
    for (uint d = lane; d < kDigits; d += lanes) histogram[d] = 0u;
    barrier();
    const uint decided = shift == 24 ? 0u : ~0u << uint(shift + 8);  // the bits chosen by the passes before
    for (uint i = lane; i < pc.count; i += lanes) {
      if (alive[i] == 0u) continue;
      for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
        const uint j = springNeighbour[k];
        if (j < i || alive[j] == 0u) continue;
        const uint bits = floatBitsToUint(squaredSpringLength(i, j));
        if ((bits & decided) == chosenBits) atomicAdd(histogram[(bits >> uint(shift)) & (kDigits - 1u)], 1u);
      }
    }
    barrier();
    if (lane == 0u) chooseDigit(uint(shift));
    barrier();
  }
  const float median = uintBitsToFloat(chosenBits);
  const float shortestSquared = kCrowdedEdge * kCrowdedEdge * median * kMore;
  const float dipThickness = initialThicknessOf(params.areaWeight);
  const uint room = 2u * STATISTICS_TERMS * pc.count - uint(GB_CROWDED_LIST);
  for (uint i = lane; i < pc.count; i += lanes) {
    if (alive[i] == 0u) continue;
    for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
      const uint j = springNeighbour[k];
      if (j < i || alive[j] == 0u) continue;
      const float squared = squaredSpringLength(i, j);
      const uint spring = springIndex[k];
      if (!(squared * kLess < shortestSquared) || !springCrowded(sqrt(squared) * kLess, restLength[spring],
                                                                 max(thickness[i], thickness[j]) * kMore, dipThickness))
        continue;
      const uint slot = atomicAdd(listed, 1u);
      if (slot < room) reduce[pc.first + uint(GB_CROWDED_LIST) + slot] = float(spring);
    }
  }
  barrier();
  if (lane != 0u) return;
  reduce[pc.first + uint(GB_CROWDED_MEDIAN)] = median;
  reduce[pc.first + uint(GB_CROWDED_LIVING)] = float(living);
  reduce[pc.first + uint(GB_CROWDED_LISTED)] = float(listed);
}
