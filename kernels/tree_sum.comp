#version 450
// One level of treeSum (cpu-reference/stages/stages.cpp): out[k] = in[2k] + in[2k+1] (or in[2k] alone for the
// odd last element), for k < ceil(n/2). The host dispatches levels until one value is left.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint k = gl_GlobalInvocationID.x;
  const uint n = pc.count;
  if (k >= (n + 1u) / 2u) return;
  if ((pc.reduceFlags & GB_REDUCE_VOLUME_IN_A) != 0u) {
    REDUCE_B(k) = 2u * k + 1u < n ? REDUCE_A(2u * k) + REDUCE_A(2u * k + 1u) : REDUCE_A(2u * k);
  } else {
    REDUCE_A(k) = 2u * k + 1u < n ? REDUCE_B(2u * k) + REDUCE_B(2u * k + 1u) : REDUCE_B(2u * k);
  }
}
