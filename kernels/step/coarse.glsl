// Where the coarse correction's lists and patch system lie (cpu-reference/solver/coarse_correction.h, Topology's patch
// lists and CoarseSystem): the lists after the colour order in the solver's list buffer, the patch system in the
// reduce buffer's coarse regions (shared_step.h). P = pc.patches, M = pc.solverParticles, R = the patch rows'
// entries.

// The lists: colourOrder (M) | patchOf (particles) | patchOffset (P + 1) | patchMembers (M) | patchRowOffset (P + 1)
// | patchRow (R).
#define PATCH_OF(i) colourOrder[pc.solverParticles + (i)]
#define PATCH_OFFSET(p) colourOrder[pc.solverParticles + pc.particles + (p)]
#define PATCH_MEMBER(k) colourOrder[pc.solverParticles + pc.particles + pc.patches + 1u + (k)]
#define PATCH_ROW_OFFSET(p) colourOrder[2u * pc.solverParticles + pc.particles + pc.patches + 1u + (p)]
#define PATCH_ROW(k) colourOrder[2u * pc.solverParticles + pc.particles + 2u * (pc.patches + 1u) + (k)]
const uint kNoPatch = 0xffffffffu;

// The patch system: blocks (9 R, column-major 3x3) | right-hand side, solution, residual, direction,
// preconditioned, product (3 P each, x, y and z blocks of P) | shortestSpring (P) | the dot products' tree sum
// (2 P, two halves).
uint coarseBase() { return reduceCoarseBlocksAt(pc.triangles); }
uint coarseVectorsBase() { return reduceCoarseVectorsAt(pc.triangles, PATCH_ROW_OFFSET(pc.patches)); }
#define COARSE_BLOCK(slot, e) reduce[coarseBase() + 9u * (slot) + (e)]
const uint kRightHandSide = 0u, kSolution = 1u, kResidual = 2u, kDirection = 3u, kPreconditioned = 4u, kProduct = 5u;
#define COARSE_SHORTEST(p) reduce[coarseVectorsBase() + 3u * uint(GB_COARSE_VECTORS) * pc.patches + (p)]
#define COARSE_DOT_A(k) reduce[coarseVectorsBase() + (3u * uint(GB_COARSE_VECTORS) + 1u) * pc.patches + (k)]
#define COARSE_DOT_B(k) reduce[coarseVectorsBase() + (3u * uint(GB_COARSE_VECTORS) + 2u) * pc.patches + (k)]

vec3 loadCoarse(uint vector, uint p) {
  const uint at = coarseVectorsBase() + 3u * vector * pc.patches + p;
  return vec3(reduce[at], reduce[at + pc.patches], reduce[at + 2u * pc.patches]);
}
void storeCoarse(uint vector, uint p, vec3 v) {
  const uint at = coarseVectorsBase() + 3u * vector * pc.patches + p;
  reduce[at] = v.x;
  reduce[at + pc.patches] = v.y;
  reduce[at + 2u * pc.patches] = v.z;
}
mat3 loadCoarseBlock(uint slot) {
  return mat3(COARSE_BLOCK(slot, 0u), COARSE_BLOCK(slot, 1u), COARSE_BLOCK(slot, 2u), COARSE_BLOCK(slot, 3u),
              COARSE_BLOCK(slot, 4u), COARSE_BLOCK(slot, 5u), COARSE_BLOCK(slot, 6u), COARSE_BLOCK(slot, 7u),
              COARSE_BLOCK(slot, 8u));
}

// rowSlot: the slot of patch `column` in patch `row`'s row (rows are sorted).
uint rowSlot(uint row, uint column) {
  uint first = PATCH_ROW_OFFSET(row), last = PATCH_ROW_OFFSET(row + 1u);
  while (first < last) {  // lower bound
    const uint middle = (first + last) / 2u;
    if (PATCH_ROW(middle) < column)
      first = middle + 1u;
    else
      last = middle;
  }
  return first;
}
