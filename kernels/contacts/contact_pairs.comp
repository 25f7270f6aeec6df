#version 450
// The device contact search, pass 4: each searched particle gathers its partners from the buckets of the 27 cells
// about its own, by findContacts' pair rule (cpu-reference/topology/collision.h; isPartner below is the C++
// PartnerRule::listPartnersIn's consider), into its row, ascending. Its count goes to the list's offsets (scanned
// next); the counters say whether a row or the list overflowed (the host then grows them and searches again).
// Gather, never scatter: each particle lists its own partners, and the rule is symmetric, so the rows are.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "contact_search.glsl"

// isOneRingNeighbour of collision.cpp.
bool isOneRingNeighbour(uint i, uint j) {
  for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k)
    if (springNeighbour[k] == j) return true;
  return false;
}

// The pair rule, with the C++ twin's float operations in its order (eigenDot) and no fused multiply-add: living film
// particles closer than the collision distance plus the pair's own margin at its closing speed |v_i - v_j| (and
// within the search's reach), across the film from each other (liesAcross), and not one-ring neighbours.
bool isPartner(uint i, uint j, float reachSquared, float frameTime, float slack) {
  const vec3 xi = LOAD3(position, i), xj = LOAD3(position, j);
  precise const vec3 d = xj - xi;
  const float lengthSquared = eigenDot(d, d);
  if (!(lengthSquared < reachSquared) || lengthSquared <= 0.0) return false;
  precise const vec3 w = LOAD3(velocity, j) - LOAD3(velocity, i);
  const float closing = sqrt(eigenDot(w, w));
  precise const float pairReach = params.collisionDistance + contactMargin(frameTime, slack, closing);
  if (!(lengthSquared < pairReach * pairReach)) return false;
  const vec3 ni = LOAD3(normal, i), nj = LOAD3(normal, j);
  return liesAcross(eigenDot(ni, d), eigenDot(nj, d), lengthSquared) && !isOneRingNeighbour(i, j);
}

// partnerRadius of collision.cpp: a distance from particle x (normal n) beyond which no particle of the bucket whose
// sheet starts at `sheet` lies across the film from it (infinite when nothing can be proved). collision.cpp gives the
// proof: with m the bucket's normal, H its height range about x along m and tilt the larger of its normals' spread and
// |n -+ m|, a partner needs sqrt(1/2) |d| < H + tilt |d|. H carries 10 um for the rounding of heights of particles
// metres from the origin, far above the float error of the pair rule's across test.
float partnerRadius(uint sheet, vec3 x, vec3 n) {
  const vec3 m =
      vec3(uintBitsToFloat(contacts[sheet + GB_SHEET_NORMAL]), uintBitsToFloat(contacts[sheet + GB_SHEET_NORMAL + 1]),
           uintBitsToFloat(contacts[sheet + GB_SHEET_NORMAL + 2]));
  const float spread = uintBitsToFloat(contacts[sheet + GB_SHEET_SPREAD]);
  const vec3 d = n - m, e = n + m;
  const float tilt = max(spread, sqrt(min(dot(d, d), dot(e, e))));
  if (!(tilt < kAcrossCosine)) return uintBitsToFloat(0x7f800000u);
  const float height = dot(m, x);
  const float offPlane = max(uintBitsToFloat(contacts[sheet + GB_SHEET_HEIGHTS + 1]) - height,
                             height - uintBitsToFloat(contacts[sheet + GB_SHEET_HEIGHTS])) +
                         1e-5;
  return offPlane / (kAcrossCosine - tilt);
}

// How far from particle x (normal n) a partner may lie in the bucket whose sheet starts at `sheet`, by
// PartnerRule::listPartnersIn's first tests: the reach, or the partner radius its sheet allows where that is less,
// each widened by a thousandth and 10 um for the rounding of the coordinates compared; 0 when x is farther than that
// from the bucket's box. On a film's flat stretches this leaves a particle only its own bucket of the 27 to read, and
// there only the particles within some 15 um of it to test further (the CPU reads a slab that wide of the bucket
// sorted along its sheet): a cell is as wide as the reach, 2.5 cm at least, and on a fine film hundreds of particles
// share one.
float partnerDistanceIn(uint sheet, vec3 x, vec3 n, float reach) {
  const vec3 lower =
      vec3(uintBitsToFloat(contacts[sheet + GB_SHEET_LOWER]), uintBitsToFloat(contacts[sheet + GB_SHEET_LOWER + 1]),
           uintBitsToFloat(contacts[sheet + GB_SHEET_LOWER + 2]));
  const vec3 upper =
      vec3(uintBitsToFloat(contacts[sheet + GB_SHEET_UPPER]), uintBitsToFloat(contacts[sheet + GB_SHEET_UPPER + 1]),
           uintBitsToFloat(contacts[sheet + GB_SHEET_UPPER + 2]));
  const vec3 outside = max(max(lower - x, x - upper), vec3(0.0));
  const float gapSquared = dot(outside, outside);
  const float widenedReach = reach * 1.001 + 1e-5;
  if (gapSquared > widenedReach * widenedReach) return 0.0;
  const float radius = min(reach, partnerRadius(sheet, x, n)) * 1.001 + 1e-5;
  return gapSquared > radius * radius ? 0.0 : radius;
}

// Puts j among the row's `count` partners, ascending; past the row's capacity it is only counted.
void insertPartner(uint row, uint count, uint capacity, uint j) {
  if (count >= capacity) return;
  uint k = count;
  for (; k > 0u && contacts[row + k - 1u] > j; --k) contacts[row + k] = contacts[row + k - 1u];
  contacts[row + k] = j;
}

void main() {
  const uint i = gl_GlobalInvocationID.x, n = pc.particles;
  if (i >= n) return;
  const ContactSearchLayout l = searchLayout();
  const uint capacity = CONTACT_HEADER(GB_CONTACT_ROW_CAPACITY), buckets = CONTACT_HEADER(GB_CONTACT_BUCKETS);
  const uint row = l.rows + i * capacity;
  const float reach = searchReach();
  const float frameTime = uintBitsToFloat(CONTACT_HEADER(GB_CONTACT_FRAME_TIME));
  const float slack = uintBitsToFloat(CONTACT_HEADER(GB_CONTACT_SLACK));
  precise const float reachSquared = reach * reach;
  uint found = 0u;
  // No search without a reach or without contact forces, as on the CPU.
  if (contacts[l.bucketOf + i] != GB_NO_BUCKET && reach > 0.0 && params.collisionStiffness > 0.0) {
    const vec3 xi = LOAD3(position, i), ni = LOAD3(normal, i);
    const ivec3 cell = cellOf(xi);
    uint visited[27];  // two of the 27 cells can share a bucket: each bucket is read once
    uint seen = 0u;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const uint bucket = bucketOfCell(cell + ivec3(dx, dy, dz), buckets);
          bool again = false;
          for (uint s = 0u; s < seen; ++s) again = again || visited[s] == bucket;
          if (again) continue;
          visited[seen++] = bucket;
          const float within = partnerDistanceIn(l.sheets + GB_CONTACT_SHEET * bucket, xi, ni, reach);
          if (!(within > 0.0)) continue;
          const float withinSquared = within * within;
          for (uint k = contacts[l.bucketStart + bucket]; k < contacts[l.bucketStart + bucket + 1u]; ++k) {
            const uint j = contacts[l.sorted + k];
            const vec3 d = LOAD3(position, j) - xi;
            if (j == i || !(dot(d, d) < withinSquared) || !isPartner(i, j, reachSquared, frameTime, slack)) continue;
            insertPartner(row, found, capacity, j);
            ++found;
          }
        }
  }
  contacts[i] = min(found, capacity);  // the row's entries, scanned into the list's offsets
  if (i == 0u) contacts[n] = 0u;       // the scan's last element: it becomes the list's entry count
  if (found > 0u) {
    atomicMax(CONTACT_HEADER(GB_CONTACT_MOST_PARTNERS), found);
    atomicAdd(CONTACT_HEADER(GB_CONTACT_PARTNER_ENTRIES), found);
  }
}
