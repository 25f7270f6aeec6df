#version 450
// The frame's statistics, pass 2: one pass of the tree (treeSum of cpu-reference/stages/stages.cpp) over every
// term's block at once, GB_TREE_PASS_LEVELS levels (GB_TREE_PASS), with max instead of + for the terms of which the
// largest is kept (GB_STAT_KEEPS_LARGEST). GB_REDUCE_STATISTICS_IN_A: the pass reads half A and writes half B.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

uint term;  // the term being summed, for combined()

float combined(float a, float b) { return GB_STAT_KEEPS_LARGEST(term) ? max(a, b) : a + b; }

void main() {
  const uint k = gl_GlobalInvocationID.x;
  const uint n = pc.count;
  if (k >= treePassOutputs(n)) return;
#define TERM_A(i) STATISTICS_A(term, i)
#define TERM_B(i) STATISTICS_B(term, i)
  for (term = 0u; term < STATISTICS_TERMS; ++term) {
    float total = 0.0;
    if ((pc.reduceFlags & GB_REDUCE_STATISTICS_IN_A) != 0u) {
      GB_TREE_PASS(total, n, TERM_A, combined);
      STATISTICS_B(term, k) = total;
    } else {
      GB_TREE_PASS(total, n, TERM_B, combined);
      STATISTICS_A(term, k) = total;
    }
  }
}
