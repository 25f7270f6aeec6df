#version 450
// coarseSolve (cpu-reference/solver/coarse_correction.cpp): block-Jacobi preconditioned conjugate gradients on the
// patch system, params.coarseIterations of them from d = 0, in one workgroup (the host dispatches one): its
// invocations share the patches, and the dot products are the C++ twin's tree sums, level by level between
// barriers.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "forces.glsl"
#include "vertex_block.glsl"
// After the headers above: coarse.glsl reads the push constants and buffers they declare.
#include "coarse.glsl"

// Every invocation's writes to the buffers are seen by the others after this.
void everyoneHere() {
  memoryBarrierBuffer();
  barrier();
}

// treeSum over the patches of a . b (vectors of coarse.glsl); every invocation gets the sum.
float coarseDot(uint a, uint b) {
  const uint t = gl_LocalInvocationID.x, w = gl_WorkGroupSize.x;
  everyoneHere();  // nobody still reads the last sum
  for (uint k = t; k < pc.patches; k += w) COARSE_DOT_A(k) = dot(loadCoarse(a, k), loadCoarse(b, k));
  everyoneHere();
  bool inA = true;
  for (uint n = pc.patches; n > 1u; n = (n + 1u) / 2u) {
    for (uint k = t; k < (n + 1u) / 2u; k += w) {
      if (inA)
        COARSE_DOT_B(k) = 2u * k + 1u < n ? COARSE_DOT_A(2u * k) + COARSE_DOT_A(2u * k + 1u) : COARSE_DOT_A(2u * k);
      else
        COARSE_DOT_A(k) = 2u * k + 1u < n ? COARSE_DOT_B(2u * k) + COARSE_DOT_B(2u * k + 1u) : COARSE_DOT_B(2u * k);
    }
    everyoneHere();
    inA = !inA;
  }
  return pc.patches == 0u ? 0.0 : (inA ? COARSE_DOT_A(0u) : COARSE_DOT_B(0u));
}

// precondition: z = D^-1 r with D the patch's diagonal block.
void precondition(uint k) {
  storeCoarse(kPreconditioned, k, solveLinear3(loadCoarseBlock(rowSlot(k, k)), loadCoarse(kResidual, k)));
}

void main() {
  const uint t = gl_LocalInvocationID.x, w = gl_WorkGroupSize.x;
  for (uint k = t; k < pc.patches; k += w) {
    storeCoarse(kSolution, k, vec3(0.0));
    storeCoarse(kResidual, k, loadCoarse(kRightHandSide, k));
    precondition(k);
    storeCoarse(kDirection, k, loadCoarse(kPreconditioned, k));
  }
  float residualDot = coarseDot(kResidual, kPreconditioned);
  for (int it = 0; it < params.coarseIterations; ++it) {
    everyoneHere();  // the product reads every patch's direction
    for (uint k = t; k < pc.patches; k += w) {
      vec3 sum = vec3(0.0);
      for (uint slot = PATCH_ROW_OFFSET(k); slot < PATCH_ROW_OFFSET(k + 1u); ++slot)
        sum += loadCoarseBlock(slot) * loadCoarse(kDirection, PATCH_ROW(slot));
      storeCoarse(kProduct, k, sum);
    }
    const float curvature = coarseDot(kDirection, kProduct);
    if (!(curvature > 0.0) || !(residualDot > 0.0)) break;  // the same for every invocation
    const float alpha = residualDot / curvature;
    for (uint k = t; k < pc.patches; k += w) {
      storeCoarse(kSolution, k, loadCoarse(kSolution, k) + alpha * loadCoarse(kDirection, k));
      storeCoarse(kResidual, k, loadCoarse(kResidual, k) - alpha * loadCoarse(kProduct, k));
      precondition(k);
    }
    const float next = coarseDot(kResidual, kPreconditioned);
    const float beta = next / residualDot;
    residualDot = next;
    for (uint k = t; k < pc.patches; k += w)
      storeCoarse(kDirection, k, loadCoarse(kPreconditioned, k) + beta * loadCoarse(kDirection, k));
  }
}
