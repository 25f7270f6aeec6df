#version 450
// The device contact search, pass 3b (after contact_sort): each occupied bucket's particles summarised as a piece of
// sheet (summariseSheet of cpu-reference/topology/collision.cpp): their box, their mean normal (each normal turned
// to agree with the first: a normal's sign does not matter to the across test), the largest distance of a normal
// from it, and the range of their heights along it. contact_pairs proves from these that a nearly flat bucket holds
// no partner of a particle farther from its box than partnerRadius.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "contact_search.glsl"

void storeSheet(uint at, vec3 lower, vec3 upper, vec3 normal, float spread, float lowest, float highest) {
  const float values[GB_CONTACT_SHEET] = float[](lower.x, lower.y, lower.z, upper.x, upper.y, upper.z, normal.x,
                                                 normal.y, normal.z, spread, lowest, highest);
  for (uint k = 0u; k < uint(GB_CONTACT_SHEET); ++k) contacts[at + k] = floatBitsToUint(values[k]);
}

void main() {
  const uint b = gl_GlobalInvocationID.x, buckets = CONTACT_HEADER(GB_CONTACT_BUCKETS);
  if (b >= buckets) return;
  const ContactSearchLayout l = searchLayout();
  const uint begin = contacts[l.bucketStart + b], end = contacts[l.bucketStart + b + 1u];
  if (begin == end) return;
  const float infinity = uintBitsToFloat(0x7f800000u);
  vec3 lower = vec3(infinity), upper = vec3(-infinity), sum = vec3(0.0);
  const vec3 first = LOAD3(normal, contacts[l.sorted + begin]);
  for (uint k = begin; k < end; ++k) {
    const uint i = contacts[l.sorted + k];
    const vec3 x = LOAD3(position, i), n = LOAD3(normal, i);
    lower = min(lower, x);
    upper = max(upper, x);
    sum += dot(n, first) < 0.0 ? -n : n;
  }
  const float length_ = length(sum);
  if (!(length_ > 0.0)) {  // no direction: nothing can be proved
    storeSheet(l.sheets + GB_CONTACT_SHEET * b, lower, upper, vec3(0.0), infinity, 0.0, 0.0);
    return;
  }
  const vec3 m = sum / length_;
  float spread = 0.0, lowest = infinity, highest = -infinity;
  for (uint k = begin; k < end; ++k) {
    const uint i = contacts[l.sorted + k];
    const vec3 n = LOAD3(normal, i), d = n - m, e = n + m;
    spread = max(spread, min(dot(d, d), dot(e, e)));
    const float height = dot(m, LOAD3(position, i));
    lowest = min(lowest, height);
    highest = max(highest, height);
  }
  storeSheet(l.sheets + GB_CONTACT_SHEET * b, lower, upper, m, sqrt(spread), lowest, highest);
}
