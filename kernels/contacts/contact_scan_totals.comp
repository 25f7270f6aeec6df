#version 450
// Exclusive prefix sum, pass 2 of 3 (contact_scan_blocks): the block sums scanned in place by one workgroup (the host
// dispatches one), each invocation over a run of them.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "contact_search.glsl"

void main() {
  const ContactSearchLayout l = searchLayout();
  const uint w = gl_WorkGroupSize.x, blockSize = w * GB_SCAN_RUN;
  const uint blocks = (pc.count + blockSize - 1u) / blockSize, perInvocation = (blocks + w - 1u) / w;
  const uint first = gl_LocalInvocationID.x * perInvocation, end = min(first + perInvocation, blocks);
  uint run = 0u;
  for (uint b = first; b < end; ++b) run += contacts[l.scanTotals + b];
  uint total;
  uint before = workgroupExclusiveScan(run, total);
  for (uint b = first; b < end; ++b) {
    const uint value = contacts[l.scanTotals + b];
    contacts[l.scanTotals + b] = before;
    before += value;
  }
}
