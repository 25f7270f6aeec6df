#version 450
// Exclusive prefix sum, pass 3 of 3 (contact_scan_blocks): each element gets the sum of the blocks before its own.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "contact_search.glsl"

void main() {
  const uint k = gl_GlobalInvocationID.x;
  if (k >= pc.count) return;
  const ContactSearchLayout l = searchLayout();
  contacts[scannedArrayAt(l) + k] += contacts[l.scanTotals + k / (gl_WorkGroupSize.x * GB_SCAN_RUN)];
}
