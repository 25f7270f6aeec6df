#version 450
// One pass of treeSum (cpu-reference/stages/stages.cpp) over the volume's n = pc.count values, GB_TREE_PASS_LEVELS
// levels a workgroup (tree_pass.glsl): out[g] the tree of in[g 2^levels ...]. The host dispatches passes until one
// value is left.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "tree_pass.glsl"

void main() {
  const uint n = pc.count;
  if (treeBlockFirst() >= n) return;  // the whole workgroup
  const bool fromA = (pc.reduceFlags & GB_REDUCE_VOLUME_IN_A) != 0u;
  float run = 0.0;
  if (fromA) {
    GB_TREE_RUN(run, n, REDUCE_A, false);
  } else {
    GB_TREE_RUN(run, n, REDUCE_B, false);
  }
  const float total = treeOfRuns(run, n, false);
  if (gl_LocalInvocationID.x != 0u) return;
  if (fromA)
    REDUCE_B(gl_WorkGroupID.x) = total;
  else
    REDUCE_A(gl_WorkGroupID.x) = total;
}
