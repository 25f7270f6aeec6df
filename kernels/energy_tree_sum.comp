#version 450
// Stage energy_budget, pass 2 (and external_drift's): one pass of treeSum (cpu-reference/stages/stages.cpp) over the
// blocks of terms at once, GB_TREE_PASS_LEVELS levels (GB_TREE_PASS); GB_REDUCE_ENERGY_IN_A: reads half A;
// GB_REDUCE_DRIFT_ONLY: sums only the drift's first DRIFT_TERMS blocks.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

float sum(float a, float b) { return a + b; }

void main() {
  const uint k = gl_GlobalInvocationID.x;
  const uint n = pc.count;
  if (k >= treePassOutputs(n)) return;
  const uint terms = (pc.reduceFlags & GB_REDUCE_DRIFT_ONLY) != 0u ? DRIFT_TERMS : ENERGY_TERMS;
  for (uint c = 0u; c < terms; ++c) {
    float total = 0.0;
#define TERM_A(i) ENERGY_A(c, i)
#define TERM_B(i) ENERGY_B(c, i)
    if ((pc.reduceFlags & GB_REDUCE_ENERGY_IN_A) != 0u) {
      GB_TREE_PASS(total, n, TERM_A, sum);
      ENERGY_B(c, k) = total;
    } else {
      GB_TREE_PASS(total, n, TERM_B, sum);
      ENERGY_A(c, k) = total;
    }
  }
}
