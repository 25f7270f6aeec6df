#version 450
// The frame's statistics, pass 2: one level of the tree over every term's block at once (treeSum of
// cpu-reference/stages/stages.cpp), out[k] = in[2k] + in[2k+1] (or in[2k] alone for the odd last element), and
// max instead of + for the terms of which the largest is kept (GB_STAT_KEEPS_LARGEST). GB_REDUCE_STATISTICS_IN_A: the
// level reads half A and writes half B.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

float combined(uint c, float a, float b) { return GB_STAT_KEEPS_LARGEST(c) ? max(a, b) : a + b; }

void main() {
  const uint k = gl_GlobalInvocationID.x;
  const uint n = pc.count;
  if (k >= (n + 1u) / 2u) return;
  const bool pair = 2u * k + 1u < n;
  for (uint c = 0u; c < STATISTICS_TERMS; ++c) {
    if ((pc.reduceFlags & GB_REDUCE_STATISTICS_IN_A) != 0u) {
      STATISTICS_B(c, k) =
          pair ? combined(c, STATISTICS_A(c, 2u * k), STATISTICS_A(c, 2u * k + 1u)) : STATISTICS_A(c, 2u * k);
    } else {
      STATISTICS_A(c, k) =
          pair ? combined(c, STATISTICS_B(c, 2u * k), STATISTICS_B(c, 2u * k + 1u)) : STATISTICS_B(c, 2u * k);
    }
  }
}
