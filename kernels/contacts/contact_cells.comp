#version 450
// The device contact search, pass 1: each searched particle counts itself into its cell's bucket and keeps its place
// there (the counting sort's count; the order within a bucket is the atomics' and does not matter: each particle's
// partners are sorted before they are listed).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "contact_search.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.particles) return;
  const ContactSearchLayout l = searchLayout();
  const vec3 x = LOAD3(position, i);
  // A particle at NaN or infinity is no one's partner (every distance test fails), and has no cell.
  const bool searched = inFilm(i) && !any(isnan(x)) && !any(isinf(x));
  uint bucket = GB_NO_BUCKET;
  if (searched) {
    bucket = bucketOfCell(cellOf(x), CONTACT_HEADER(GB_CONTACT_BUCKETS));
    contacts[l.slot + i] = atomicAdd(contacts[l.bucketStart + bucket], 1u);
  }
  contacts[l.bucketOf + i] = bucket;
}
