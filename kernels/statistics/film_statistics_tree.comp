#version 450
// The frame's statistics, pass 2: one pass of the tree (treeSum of cpu-reference/stages/stages.cpp) over every
// term's block at once, GB_TREE_PASS_LEVELS levels a workgroup (tree_pass.glsl), with max instead of + for the terms
// of which the largest is kept (GB_STAT_KEEPS_LARGEST). GB_REDUCE_STATISTICS_IN_A: the pass reads half A and writes
// half B.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "tree_pass.glsl"

void main() {
  const uint n = pc.count;
  if (treeBlockFirst() >= n) return;  // the whole workgroup
  const bool fromA = (pc.reduceFlags & GB_REDUCE_STATISTICS_IN_A) != 0u;
  for (uint c = 0u; c < STATISTICS_TERMS; ++c) {
    const bool largest = GB_STAT_KEEPS_LARGEST(c);
    float run = 0.0;
#define TERM_A(i) STATISTICS_A(c, i)
#define TERM_B(i) STATISTICS_B(c, i)
    if (fromA) {
      GB_TREE_RUN(run, n, TERM_A, largest);
    } else {
      GB_TREE_RUN(run, n, TERM_B, largest);
    }
    const float total = treeOfRuns(run, n, largest);
    if (gl_LocalInvocationID.x != 0u) continue;
    if (fromA)
      STATISTICS_B(c, gl_WorkGroupID.x) = total;
    else
      STATISTICS_A(c, gl_WorkGroupID.x) = total;
  }
}
