#version 450
// The device contact search, pass 5 (after the partner counts' scan into the list's offsets): each particle writes
// its row into the packed list (Topology::contacts) with each pair's rest distance (contactRestDistanceAfter, from
// the rest distance the pair had in the previous list). Nothing is written when the list would not fit: the host
// sees the overflow in the counters, grows the buffer and searches again.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "contact_search.glsl"

// previousRestDistance of cpu-reference/topology/collision.cpp: the rest distance pair (i, j) had in the previous
// list (packed at `at` for `particles` particles), or 0 when it was not listed. A binary search of i's sorted row.
float previousRestDistance(uint at, uint particles, uint i, uint j) {
  if (i >= particles || j >= particles) return 0.0;
  const uint partners = at + particles + 1u;
  uint low = contacts[at + i], high = contacts[at + i + 1u];
  while (low < high) {
    const uint middle = (low + high) / 2u;
    if (contacts[partners + middle] < j)
      low = middle + 1u;
    else
      high = middle;
  }
  if (low == contacts[at + i + 1u] || contacts[partners + low] != j) return 0.0;
  return uintBitsToFloat(contacts[partners + contacts[at + particles] + low]);
}

void main() {
  const uint i = gl_GlobalInvocationID.x, n = pc.particles;
  if (i >= n) return;
  const ContactSearchLayout l = searchLayout();
  const uint total = contacts[n], capacity = CONTACT_HEADER(GB_CONTACT_ROW_CAPACITY);
  if (total > CONTACT_HEADER(GB_CONTACT_ENTRY_CAPACITY)) return;
  const uint previousParticles = CONTACT_HEADER(GB_CONTACT_PREVIOUS_PARTICLES);
  const vec3 xi = LOAD3(position, i);
  for (uint k = contacts[i]; k < contacts[i + 1u]; ++k) {
    const uint j = contacts[l.rows + i * capacity + (k - contacts[i])];
    precise const vec3 d = xi - LOAD3(position, j);
    const float separation = sqrt(eigenDot(d, d));
    const float rest = contactRestDistanceAfter(params.collisionDistance,
                                                previousRestDistance(l.previous, previousParticles, i, j), separation);
    contacts[n + 1u + k] = j;
    contacts[n + 1u + total + k] = floatBitsToUint(rest);
  }
}
