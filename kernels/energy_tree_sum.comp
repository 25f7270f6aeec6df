#version 450
// Stage energy_budget, pass 2 (and external_drift's): one level of treeSum (cpu-reference/stages/stages.cpp) over the
// blocks of terms at once, out[k] = in[2k] + in[2k+1] (or in[2k] alone for the odd last element);
// GB_REDUCE_ENERGY_IN_A: reads half A; GB_REDUCE_DRIFT_ONLY: sums only the drift's first DRIFT_TERMS blocks.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint k = gl_GlobalInvocationID.x;
  const uint n = pc.count;
  if (k >= (n + 1u) / 2u) return;
  const uint terms = (pc.reduceFlags & GB_REDUCE_DRIFT_ONLY) != 0u ? DRIFT_TERMS : ENERGY_TERMS;
  for (uint c = 0u; c < terms; ++c) {
    if ((pc.reduceFlags & GB_REDUCE_ENERGY_IN_A) != 0u) {
      ENERGY_B(c, k) = 2u * k + 1u < n ? ENERGY_A(c, 2u * k) + ENERGY_A(c, 2u * k + 1u) : ENERGY_A(c, 2u * k);
    } else {
      ENERGY_A(c, k) = 2u * k + 1u < n ? ENERGY_B(c, 2u * k) + ENERGY_B(c, 2u * k + 1u) : ENERGY_B(c, 2u * k);
    }
  }
}
