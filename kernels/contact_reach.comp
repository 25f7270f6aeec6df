#version 450
// The reach of ContactSearch::find (cpu-reference/topology/collision.cpp), in one workgroup (the host dispatches
// one): the collision distance plus the margin (contactMargin) at twice the fastest speed about the film's mean
// velocity, which bounds every pair's closing speed |v_i - v_j| <= |v_i - mean| + |v_j - mean|. The sums are a fixed
// tree over the invocations' strided partial sums, the same on every run; they round differently from the CPU's
// serial sum, which moves the reach by float rounding only: a pair's own reach (contact_pairs) decides the list.
// Also zeroes the counters contact_pairs adds to.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "contact_search.glsl"

shared vec4 reachPartial[gl_WorkGroupSize.x];

// The tree sum (w: the largest) of reachPartial over the workgroup; every invocation gets it.
vec4 workgroupTree(bool largest) {
  const uint t = gl_LocalInvocationID.x;
  for (uint n = gl_WorkGroupSize.x; n > 1u; n = (n + 1u) / 2u) {
    barrier();
    const uint half_ = (n + 1u) / 2u;
    if (t + half_ < n) {
      const vec4 a = reachPartial[t], b = reachPartial[t + half_];
      reachPartial[t] = largest ? max(a, b) : a + b;
    }
  }
  barrier();
  const vec4 result = reachPartial[0];
  barrier();
  return result;
}

void main() {
  const uint t = gl_LocalInvocationID.x, w = gl_WorkGroupSize.x, n = pc.particles;
  vec4 sum = vec4(0.0);  // velocity, living count
  for (uint i = t; i < n; i += w)
    if (inFilm(i)) sum += vec4(LOAD3(velocity, i), 1.0);
  reachPartial[t] = sum;
  const vec4 total = workgroupTree(false);
  const vec3 mean = total.w > 0.0 ? total.xyz / total.w : vec3(0.0);
  float fastest = 0.0;
  for (uint i = t; i < n; i += w)
    if (inFilm(i)) fastest = max(fastest, length(LOAD3(velocity, i) - mean));
  reachPartial[t] = vec4(fastest);
  fastest = workgroupTree(true).x;
  if (t == 0u) {
    const float frameTime = uintBitsToFloat(CONTACT_HEADER(GB_CONTACT_FRAME_TIME));
    const float slack = uintBitsToFloat(CONTACT_HEADER(GB_CONTACT_SLACK));
    CONTACT_HEADER(GB_CONTACT_REACH) =
        floatBitsToUint(params.collisionDistance + contactMargin(frameTime, slack, 2.0 * fastest));
    CONTACT_HEADER(GB_CONTACT_MOST_PARTNERS) = 0u;
    CONTACT_HEADER(GB_CONTACT_PARTNER_ENTRIES) = 0u;
  }
}
