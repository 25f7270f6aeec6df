#version 450
// The reach of ContactSearch::find (cpu-reference/topology/collision.cpp): the collision distance plus the margin
// (contactMargin) at twice the fastest speed about the film's mean velocity, which bounds every pair's closing speed
// |v_i - v_j| <= |v_i - mean| + |v_j - mean|. Three passes (PushBlock::reduceFlags), the first two over runs of
// GB_REACH_RUN particles an invocation, a workgroup a run (contactReachGroups), so that a million particles are read
// by many workgroups at once: each run's velocity sum and living count; each run's fastest speed about the mean,
// every workgroup summing the runs' sums itself; then, in one workgroup, the largest of those and the reach, written
// to the header with the counters contact_pairs adds to zeroed. Every sum is a fixed tree, the same on every run;
// they round differently from the CPU's serial sum, which moves the reach by float rounding only: a pair's own reach
// (contact_pairs) decides the list.
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

// The runs' partial results in the sheets region: a vec4 (velocity sum, living count) a run, then a float (fastest).
uint runSumAt(ContactSearchLayout l, uint run) { return l.sheets + 4u * run; }
uint runFastestAt(ContactSearchLayout l, uint runs, uint run) { return l.sheets + 4u * runs + run; }
vec4 loadRunSum(ContactSearchLayout l, uint run) {
  const uint at = runSumAt(l, run);
  return uintBitsToFloat(uvec4(contacts[at], contacts[at + 1u], contacts[at + 2u], contacts[at + 3u]));
}

// The particles of this invocation in this workgroup's run: i = first + k * w for k < GB_REACH_RUN, below `n`.
uint runFirst() { return gl_WorkGroupID.x * gl_WorkGroupSize.x * GB_REACH_RUN + gl_LocalInvocationID.x; }

void sumRun(ContactSearchLayout l, uint n) {
  vec4 sum = vec4(0.0);  // velocity, living count
  for (uint k = 0u, i = runFirst(); k < GB_REACH_RUN && i < n; ++k, i += gl_WorkGroupSize.x)
    if (inFilm(i)) sum += vec4(LOAD3(velocity, i), 1.0);
  reachPartial[gl_LocalInvocationID.x] = sum;
  const vec4 total = workgroupTree(false);
  if (gl_LocalInvocationID.x == 0u) {
    const uvec4 bits = floatBitsToUint(total);
    const uint at = runSumAt(l, gl_WorkGroupID.x);
    for (uint c = 0u; c < 4u; ++c) contacts[at + c] = bits[c];
  }
}

void fastestInRun(ContactSearchLayout l, uint n, uint runs) {
  vec4 sum = vec4(0.0);
  for (uint r = gl_LocalInvocationID.x; r < runs; r += gl_WorkGroupSize.x) sum += loadRunSum(l, r);
  reachPartial[gl_LocalInvocationID.x] = sum;
  const vec4 total = workgroupTree(false);
  const vec3 mean = total.w > 0.0 ? total.xyz / total.w : vec3(0.0);
  float fastest = 0.0;
  for (uint k = 0u, i = runFirst(); k < GB_REACH_RUN && i < n; ++k, i += gl_WorkGroupSize.x)
    if (inFilm(i)) fastest = max(fastest, length(LOAD3(velocity, i) - mean));
  reachPartial[gl_LocalInvocationID.x] = vec4(fastest);
  fastest = workgroupTree(true).x;
  if (gl_LocalInvocationID.x == 0u) contacts[runFastestAt(l, runs, gl_WorkGroupID.x)] = floatBitsToUint(fastest);
}

void writeReach(ContactSearchLayout l, uint runs) {
  float fastest = 0.0;
  for (uint r = gl_LocalInvocationID.x; r < runs; r += gl_WorkGroupSize.x)
    fastest = max(fastest, uintBitsToFloat(contacts[runFastestAt(l, runs, r)]));
  reachPartial[gl_LocalInvocationID.x] = vec4(fastest);
  fastest = workgroupTree(true).x;
  if (gl_LocalInvocationID.x == 0u) {
    const float frameTime = uintBitsToFloat(CONTACT_HEADER(GB_CONTACT_FRAME_TIME));
    const float slack = uintBitsToFloat(CONTACT_HEADER(GB_CONTACT_SLACK));
    CONTACT_HEADER(GB_CONTACT_REACH) =
        floatBitsToUint(params.collisionDistance + contactMargin(frameTime, slack, 2.0 * fastest));
    CONTACT_HEADER(GB_CONTACT_MOST_PARTNERS) = 0u;
    CONTACT_HEADER(GB_CONTACT_PARTNER_ENTRIES) = 0u;
  }
}

void main() {
  const ContactSearchLayout l = searchLayout();
  const uint n = pc.particles, runs = contactReachGroups(n, gl_WorkGroupSize.x);
  if ((pc.reduceFlags & GB_REACH_FINAL) != 0u)
    writeReach(l, runs);
  else if ((pc.reduceFlags & GB_REACH_FASTEST) != 0u)
    fastestInRun(l, n, runs);
  else
    sumRun(l, n);
}
