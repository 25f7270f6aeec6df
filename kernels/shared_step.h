// One definition, compiled as C++ (host/) and GLSL (every compute shader), of what the GPU stages receive
// besides the parameter block: the per-step uniforms, the push constants, the buffer bindings (from the list in
// device_data.h) and the regions of the reduce buffer.
// Vectors are vec4 (w unused) so that std430 and C++ agree without hidden padding; host/ static_asserts
// the offsets and a device test checks them.
#ifdef __cplusplus
#pragma once
#include <cstdint>
namespace gb::gpu {
struct alignas(16) vec4 {
  float x, y, z, w;
};
using uint = uint32_t;
#endif

// StepUniforms of cpu-reference/stages/stages.h, one per step of a submitted batch.
struct StepUniformsBlock {
  vec4 leftPosition;  // wand tips at the start of the substep (Eq. 5)
  vec4 leftVelocity;
  vec4 rightPosition;
  vec4 rightVelocity;
  vec4 wireCenter;  // wire frame at the end of the substep (boundary particles)
  vec4 wireAxis;
  vec4 wireDown;
  vec4 volumeOrigin;  // apex of the volume's cone decomposition
  float dt;           // substep (s)
  float leftInflowWeight;
  float airVolume;      // V_wm of Eq. (6)
  float wandAlignment;  // MAX(cos theta, 0) of Eq. (5)
  float wireHalfWidth;
  float wireDepth;
  float referenceVolume;  // V_0 of Eq. (11)
  int wireKind;           // ToolKind: 0 two wands, 1 ring
  uint closed;            // 1 for a closed bubble
  float drainageDt;       // drainage time of this substep, 0: no drainage
  float wireArea;         // Area_wm of Eq. (6): turns the air flow into the air's speed (air coupling)
  uint pad2;
};

// Push constants of every stage (32 bytes of the 128 guaranteed).
struct PushBlock {
  uint count;            // elements of the dispatch: particles, triangles, reduction inputs, or a colour's particles
  uint particles;        // particle count, the stride between the x, y and z blocks of a vector attribute
  uint stepIndex;        // which StepUniformsBlock of the batch
  uint reduceFlags;      // GB_REDUCE_* bits: where the sums a kernel reads lie, and what it sums
  uint triangles;        // triangle count, the stride of the per-triangle vector blocks and of the tree-sum halves
  uint first;            // vertex_block_descent: where the colour's particles start in colourOrder; the energy
                         // stages: where the energy terms start in the reduce buffer (reduceEnergyTermsAt)
  uint patches;          // coarse correction: the patch count P (Topology::patchOffset)
  uint solverParticles;  // the solver's particle count M (Topology::colourOrder), where the patch lists start
};

#ifdef __cplusplus
}  // namespace gb::gpu
#endif

// PushBlock::reduceFlags, one meaning per bit in every kernel. A tree sum ping-pongs between the halves A and B of
// its region; a flag says which half holds what a kernel reads (a level's input, or a finished sum).
#define GB_REDUCE_VOLUME_IN_A 1u    // the volume's tree sum: half A holds it (else half B)
#define GB_REDUCE_ENERGY_IN_A 2u    // the energy terms' tree sum: half A holds it (else half B)
#define GB_REDUCE_AT_STEP_START 4u  // triangle_volume: the volume at the step's start (the energy budget's)
#define GB_REDUCE_DRIFT_ONLY 8u     // energy_tree_sum: only external_drift's first GB_DRIFT_TERMS blocks

// The energy budget's slack (cpu-reference/solver/energy_budget.h says why this much), one value for both backends.
#define GB_ENERGY_BUDGET_TOLERANCE 1e-4
// The energy budget's terms per particle (ParticleEnergy of cpu-reference/solver/energy_budget.h): start, kinetic,
// held, mass, momentum x, y, z, expected momentum x, y, z.
#define GB_ENERGY_TERMS 10
// A closed film's drift terms per particle (externalDrift of cpu-reference/solver/implicit_euler.h): mass, force x, y,
// z. They use the first blocks of the energy terms' region, before the budget does.
#define GB_DRIFT_TERMS 4

// The reduce buffer (GB_BINDING_REDUCE) holds, one after the other, with T triangles, R patch-row entries, P patches
// and N particles (floats):
//   tree sum        the volume's tree sum, halves A and B of T floats each (tree_sum, triangle_volume);
//   coarse blocks   the coarse correction's 3x3 blocks, 9 R, column-major (kernels/coarse.glsl);
//   coarse vectors  its right-hand side, solution, residual, direction, preconditioned, product (3 P each, x, y and
//                   z blocks of P), the patches' shortest springs (P), its dot products' halves A and B (P each);
//   energy terms    the energy budget's terms, halves A and B of GB_ENERGY_TERMS blocks of N floats;
//   energy slots    the bubble's volume before the step, then the VelocityBudget (GB_SLOT_*).
// The functions give where each region starts; the host sizes the buffer and passes the energy terms' start in
// PushBlock::first, the kernels address the regions from them.
#define GB_COARSE_VECTORS 6                                  // right-hand side ... product, 3 P floats each
#define GB_COARSE_VECTOR_FLOATS (3 * GB_COARSE_VECTORS + 3)  // per patch: the vectors, shortest spring, 2 dot halves
#define GB_SLOT_VOLUME_BEFORE 0                              // the bubble's volume before the step
#define GB_SLOT_SCALE 1                                      // VelocityBudget::scale
#define GB_SLOT_CENTRE 2                                     // VelocityBudget::centre, x y z
#define GB_SLOT_SHIFT 5                                      // VelocityBudget::shift, x y z
#define GB_SLOT_RELEASED 8                                   // VelocityBudget::released
#define GB_ENERGY_SLOTS 9

#ifdef __cplusplus
namespace gb::gpu {
#define GB_REGION inline constexpr
GB_REGION uint maxOf(uint a, uint b) { return a > b ? a : b; }
#else
#define GB_REGION
uint maxOf(uint a, uint b) { return max(a, b); }
#endif
GB_REGION uint reduceHalfB(uint triangleCount) { return maxOf(triangleCount, 1u); }
GB_REGION uint reduceCoarseBlocksAt(uint triangleCount) { return 2u * maxOf(triangleCount, 1u); }
GB_REGION uint reduceCoarseVectorsAt(uint triangleCount, uint rowEntries) {
  return reduceCoarseBlocksAt(triangleCount) + 9u * rowEntries;
}
GB_REGION uint reduceEnergyTermsAt(uint triangleCount, uint rowEntries, uint patchCount) {
  return reduceCoarseVectorsAt(triangleCount, rowEntries) + uint(GB_COARSE_VECTOR_FLOATS) * patchCount;
}
GB_REGION uint reduceEnergySlotsAt(uint termsAt, uint particleCount) {
  return termsAt + 2u * uint(GB_ENERGY_TERMS) * particleCount;
}
#undef GB_REGION
#ifdef __cplusplus
}  // namespace gb::gpu
#endif

#ifdef __cplusplus
// The storage buffer bindings of descriptor set 0, numbered as device_data.h lists them.
namespace gb::gpu {
enum Binding : int {
#define GB_BUFFER(binding, NAME, element, declarator, access) GB_BINDING_##NAME,
#define GB_PARTICLE_ARRAY(binding, NAME, name, components, element, access, transfer, created) GB_BINDING_##NAME,
#define GB_PARTICLE_BLOCK(NAME, block, name, components, transfer, created)
#include "device_data.h"
#undef GB_BUFFER
#undef GB_PARTICLE_ARRAY
#undef GB_PARTICLE_BLOCK
  GB_BINDING_COUNT
};
// Each line of device_data.h gives its own number: they count 0, 1, 2, ...
#define GB_BUFFER(binding, NAME, element, declarator, access) \
  static_assert(GB_BINDING_##NAME == (binding), "device_data.h: " #NAME " is not numbered as it is listed");
#define GB_PARTICLE_ARRAY(binding, NAME, name, components, element, access, transfer, created) \
  GB_BUFFER(binding, NAME, element, name, access)
#define GB_PARTICLE_BLOCK(NAME, block, name, components, transfer, created)
#include "device_data.h"
#undef GB_BUFFER
#undef GB_PARTICLE_ARRAY
#undef GB_PARTICLE_BLOCK
static_assert(GB_BINDING_COUNT <= 32, "lavapipe allows 32 storage buffers per stage: pack before adding");
}  // namespace gb::gpu
#endif
