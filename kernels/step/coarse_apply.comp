#version 450
// coarseApply (cpu-reference/solver/coarse_correction.cpp), per particle: a solver particle moves by its patch's
// solution, shortened to the trust region of the patch's shortest spring, then onto the floor.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "forces.glsl"
#include "vertex_block.glsl"
// After the headers above: coarse.glsl reads the push constants and buffers they declare.
#include "coarse.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const uint ownPatch = PATCH_OF(i);
  if (ownPatch == kNoPatch || alive[i] == 0u) return;
  const vec3 move = withinTrustRegion(loadCoarse(kSolution, ownPatch), kPatchTrustScale * COARSE_SHORTEST(ownPatch));
  if (any(isnan(move)) || any(isinf(move))) return;
  vec3 next = LOAD3(position, i) + move;
  next.y = max(next.y, 0.0);
  STORE3(position, i, next);
}
