#version 450
// coarseAssemble (cpu-reference/solver/coarse_correction.cpp), one patch per invocation: its row of the patch system
// P^T H P and its entry of -P^T g at the current positions, gathered over its particles and their one-rings in the
// C++ twin's order.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "forces.glsl"
#include "vertex_block.glsl"
// After the headers above: coarse.glsl reads the push constants and buffers they declare.
#include "coarse.glsl"

// springCouplingBlock: the off-diagonal block of spring k of i's one-ring.
mat3 springCouplingBlock(float h, uint i, uint k) {
  const uint j = springNeighbour[k];
  const vec3 d = LOAD3(position, j) - LOAD3(position, i);
  const float len = length(d);
  if (!(len > 0.0)) return mat3(0.0);
  const vec3 dir = d / len;
  float along = params.springDamping / h, transverse = 0.0;
  if (params.tensionModel != 1) {
    const float stiffness = 0.5 * (elasticity[i] + elasticity[j]);
    transverse = stiffness * max(0.0, 1.0 - restLength[springIndex[k]] / len);
    along += stiffness - transverse;
  }
  return -(along * outerProduct(dir, dir) + transverse * mat3(1.0));
}

// triangleCouplingBlock: the off-diagonal block between corners c and l of triangle t (physical model), by the
// C++ twin's closed form.
mat3 triangleCouplingBlock(uint t, uint c, uint l) {
  const vec3 x0 = LOAD3(position, triangles[3u * t]), x1 = LOAD3(position, triangles[3u * t + 1u]),
             x2 = LOAD3(position, triangles[3u * t + 2u]);
  const vec3 normal = cross(x1 - x0, x2 - x0);
  const float twiceArea = length(normal);
  if (!(twiceArea > 0.0)) return mat3(0.0);
  const vec3 edges[3] = vec3[3](x2 - x1, x0 - x2, x1 - x0), n = normal / twiceArea;
  const vec3 a = edges[c], b = edges[l];
  const mat3 sandwich = outerProduct(b, a) - dot(a, b) * mat3(1.0) + outerProduct(cross(a, n), cross(b, n));
  const float startTension =
      (elasticity[triangles[3u * t]] + elasticity[triangles[3u * t + 1u]] + elasticity[triangles[3u * t + 2u]]) / 3.0;
  const TriangleTension law = triangleTensionOf(startTension, triangleAreaAtStart(t), 0.5 * twiceArea);
  return -(law.tension / (2.0 * twiceArea)) * sandwich + (0.25 * law.slope) * outerProduct(cross(a, n), cross(b, n));
}

void addToBlock(uint slot, mat3 m) {
  for (uint c = 0u; c < 3u; ++c)
    for (uint r = 0u; r < 3u; ++r) COARSE_BLOCK(slot, 3u * c + r) += m[c][r];
}

void main() {
  const uint ownPatch = gl_GlobalInvocationID.x;
  if (ownPatch >= pc.count) return;
  const StepUniformsBlock u = steps[pc.stepIndex];
  for (uint slot = PATCH_ROW_OFFSET(ownPatch); slot < PATCH_ROW_OFFSET(ownPatch + 1u); ++slot)
    for (uint e = 0u; e < 9u; ++e) COARSE_BLOCK(slot, e) = 0.0;
  const uint diagonal = rowSlot(ownPatch, ownPatch);
  vec3 rightHandSide = vec3(0.0);
  float shortest = 1.0 / 0.0;  // +infinity, as the C++ twin's
  for (uint m = PATCH_OFFSET(ownPatch); m < PATCH_OFFSET(ownPatch + 1u); ++m) {
    const uint i = PATCH_MEMBER(m);
    if (alive[i] == 0u) continue;  // died in a burst since the patches were made
    objectiveBlock(u, i);
    addToBlock(diagonal, hessian);
    rightHandSide -= gradient;
    shortest = min(shortest, shortestSpring);
    for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
      const uint other = PATCH_OF(springNeighbour[k]);
      if (other != kNoPatch) addToBlock(rowSlot(ownPatch, other), springCouplingBlock(u.dt, i, k));
    }
    if (params.tensionModel != 1) continue;
    for (uint k = triangleOffset[i]; k < triangleOffset[i + 1u]; ++k) {
      const uint corner = triangleCorner[k], t = corner / 3u, c = corner % 3u;
      for (uint l = 0u; l < 3u; ++l) {
        const uint other = PATCH_OF(triangles[3u * t + l]);
        if (l != c && other != kNoPatch) addToBlock(rowSlot(ownPatch, other), triangleCouplingBlock(t, c, l));
      }
    }
  }
  storeCoarse(kRightHandSide, ownPatch, rightHandSide);
  COARSE_SHORTEST(ownPatch) = shortest;
}
