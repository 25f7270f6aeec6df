// What the device contact search's kernels (contact_*.comp) share: its regions of the contacts buffer
// (shared_step.h), the cells, and the workgroup scan. After common.glsl.

#define CONTACT_HEADER(slot) contacts[pc.first + uint(slot)]

ContactSearchLayout searchLayout() {
  return contactSearchLayout(pc.first, pc.particles, CONTACT_HEADER(GB_CONTACT_BUCKETS),
                             CONTACT_HEADER(GB_CONTACT_ROW_CAPACITY));
}

float searchReach() { return uintBitsToFloat(CONTACT_HEADER(GB_CONTACT_REACH)); }

// inFilm of cpu-reference/topology/collision.cpp: living and still part of the film (a particle whose triangles all
// tore is not).
bool inFilm(uint i) { return alive[i] != 0u && triangleOffset[i + 1u] > triangleOffset[i]; }

// a . b as the C++ twins' Eigen sums a 3-vector's terms: x + (y + z), without fused multiply-adds.
float eigenDot(vec3 a, vec3 b) {
  precise const float sum = a.x * b.x + (a.y * b.y + a.z * b.z);
  return sum;
}

// The cells are the reach and a thousandth wider: x times the rounded inverse of the width is monotonic in x, and a
// width a thousandth over the reach keeps every pair within the reach within one cell of each other along each axis
// through the rounding of that product. So the 27 cells about a particle's hold all its partners.
float inverseCellWidth() { return 1.0 / (searchReach() * 1.001 + 1e-6); }
ivec3 cellOf(vec3 x) { return ivec3(floor(x * inverseCellWidth())); }

// A cell's bucket: its coordinates mixed (a multiplicative hash, then murmur3's finaliser) into B buckets. Cells that
// share a bucket are told apart by the pair rule's distance test.
uint bucketOfCell(ivec3 cell, uint buckets) {
  const uvec3 c = uvec3(cell);
  uint h = (c.x * 73856093u) ^ (c.y * 19349663u) ^ (c.z * 83492791u);
  h ^= h >> 16u;
  h *= 0x85ebca6bu;
  h ^= h >> 13u;
  h *= 0xc2b2ae35u;
  h ^= h >> 16u;
  return h & (buckets - 1u);
}

// The exclusive prefix sum of `value` over the workgroup's invocations, and their total. Every invocation of the
// workgroup calls it (it holds barriers). Integer sums: exact in any order.
shared uint scanPartial[gl_WorkGroupSize.x];
uint workgroupExclusiveScan(uint value, out uint total) {
  const uint t = gl_LocalInvocationID.x, w = gl_WorkGroupSize.x;
  scanPartial[t] = value;
  barrier();
  for (uint offset = 1u; offset < w; offset *= 2u) {  // Hillis and Steele: after the step, t holds offset * 2 values
    const uint before = t >= offset ? scanPartial[t - offset] : 0u;
    barrier();
    scanPartial[t] += before;
    barrier();
  }
  total = scanPartial[w - 1u];
  const uint inclusive = scanPartial[t];
  barrier();  // everyone has read before the next call writes
  return inclusive - value;
}

// Where the array a scan works on starts (PushBlock::reduceFlags): the partner counts at the list's start, which the
// scan turns into its offsets, or the bucket counts.
uint scannedArrayAt(ContactSearchLayout l) { return (pc.reduceFlags & GB_SCAN_ROWS) != 0u ? 0u : l.bucketStart; }
