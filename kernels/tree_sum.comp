#version 450
// One pass of treeSum (cpu-reference/stages/stages.cpp) over the volume's n = pc.count values: GB_TREE_PASS_LEVELS
// levels, out[k] the tree of in[k 2^levels ...] (GB_TREE_PASS). The host dispatches passes until one value is left.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

float sum(float a, float b) { return a + b; }

void main() {
  const uint k = gl_GlobalInvocationID.x;
  const uint n = pc.count;
  if (k >= treePassOutputs(n)) return;
  float total = 0.0;
  if ((pc.reduceFlags & GB_REDUCE_VOLUME_IN_A) != 0u) {
    GB_TREE_PASS(total, n, REDUCE_A, sum);
    REDUCE_B(k) = total;
  } else {
    GB_TREE_PASS(total, n, REDUCE_B, sum);
    REDUCE_A(k) = total;
  }
}
