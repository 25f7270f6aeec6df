#version 450
// The device contact search, pass 3 (after the bucket counts' scan): each searched particle into its place in its
// bucket's run of `sorted`.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "contact_search.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.particles) return;
  const ContactSearchLayout l = searchLayout();
  const uint bucket = contacts[l.bucketOf + i];
  if (bucket == GB_NO_BUCKET) return;
  contacts[l.sorted + contacts[l.bucketStart + bucket] + contacts[l.slot + i]] = i;
}
