#version 450
// Stage energy_budget, pass 2 (and external_drift's): one pass of treeSum (cpu-reference/stages/stages.cpp) over the
// blocks of terms at once, GB_TREE_PASS_LEVELS levels a workgroup (tree_pass.glsl); GB_REDUCE_ENERGY_IN_A: reads
// half A; GB_REDUCE_DRIFT_ONLY: sums only the drift's first DRIFT_TERMS blocks.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "tree_pass.glsl"

void main() {
  const uint n = pc.count;
  if (treeBlockFirst() >= n) return;  // the whole workgroup
  const uint terms = (pc.reduceFlags & GB_REDUCE_DRIFT_ONLY) != 0u ? DRIFT_TERMS : ENERGY_TERMS;
  const bool fromA = (pc.reduceFlags & GB_REDUCE_ENERGY_IN_A) != 0u;
  for (uint c = 0u; c < terms; ++c) {
    float run = 0.0;
#define TERM_A(i) ENERGY_A(c, i)
#define TERM_B(i) ENERGY_B(c, i)
    if (fromA) {
      GB_TREE_RUN(run, n, TERM_A, false);
    } else {
      GB_TREE_RUN(run, n, TERM_B, false);
    }
    const float total = treeOfRuns(run, n, false);
    if (gl_LocalInvocationID.x != 0u) continue;
    if (fromA)
      ENERGY_B(c, gl_WorkGroupID.x) = total;
    else
      ENERGY_A(c, gl_WorkGroupID.x) = total;
  }
}
