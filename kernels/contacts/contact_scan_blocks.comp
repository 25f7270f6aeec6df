#version 450
// Exclusive prefix sum of pc.count uints in place (the bucket counts, or the partner counts: scannedArrayAt), pass 1
// of 3: each workgroup scans its block of w GB_SCAN_RUN elements and leaves the block's sum in the scan totals;
// contact_scan_totals scans those, contact_scan_add adds them back.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "contact_search.glsl"

void main() {
  const ContactSearchLayout l = searchLayout();
  const uint at = scannedArrayAt(l), n = pc.count;
  const uint first = gl_GlobalInvocationID.x * GB_SCAN_RUN;
  uint run = 0u;
  for (uint k = first; k < min(first + GB_SCAN_RUN, n); ++k) run += contacts[at + k];
  uint blockSum;
  uint before = workgroupExclusiveScan(run, blockSum);  // every invocation, in range or not: it holds barriers
  for (uint k = first; k < min(first + GB_SCAN_RUN, n); ++k) {
    const uint value = contacts[at + k];
    contacts[at + k] = before;
    before += value;
  }
  if (gl_LocalInvocationID.x == 0u) contacts[l.scanTotals + gl_WorkGroupID.x] = blockSum;
}
