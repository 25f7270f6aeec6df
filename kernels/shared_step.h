// One definition, compiled as C++ (host/) and GLSL (every compute shader), of what the GPU stages receive
// besides the parameter block: the per-substep uniforms, the push constants and the buffer bindings.
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

// StepUniforms of cpu-reference/stages.h, one per substep of a submitted batch.
struct StepUniformsBlock {
  vec4 leftPosition;  // wand tips at the start of the substep (Eq. 5)
  vec4 leftVelocity;
  vec4 rightPosition;
  vec4 rightVelocity;
  vec4 frameCenter;  // wire frame at the end of the substep (boundary particles)
  vec4 frameAxis;
  vec4 frameDown;
  vec4 volumeOrigin;  // apex of the volume's cone decomposition
  float dt;           // substep (s)
  float leftInflowWeight;
  float airVolume;      // V_wm of Eq. (6)
  float wandAlignment;  // MAX(cos theta, 0) of Eq. (5)
  float frameHalfWidth;
  float frameDepth;
  float referenceVolume;  // V_0 of Eq. (11)
  int frameKind;          // ToolKind: 0 two wands, 1 ring
  uint closed;            // 1 for a closed bubble
  float drainageDt;       // drainage time of this substep, 0: no drainage
  float frameArea;        // Area_wm of Eq. (6): turns the air flow into the air's speed (air coupling)
  uint pad2;
};

// Push constants of every stage (32 bytes of the 128 guaranteed).
struct PushBlock {
  uint count;            // elements of the dispatch: particles, triangles, reduction inputs, or a colour's particles
  uint particles;        // particle count, the stride between the x, y and z blocks of a vector attribute
  uint stepIndex;        // which StepUniformsBlock of the batch
  uint reduceFlags;      // tree_sum: 1 reads half A writes half B, 0 the reverse; forces: 1 if the volume is in A
  uint triangles;        // triangle count, the stride of the per-triangle vector blocks and of the reduce halves
  uint first;            // vertex_block_descent: where the colour's particles start in colourOrder
  uint patches;          // coarse correction: the patch count P (Topology::patchOffset)
  uint solverParticles;  // the solver's particle count M (Topology::colourOrder), where the patch lists start
};

#ifdef __cplusplus
}  // namespace gb::gpu
#endif

// The energy budget's slack (cpu-reference/energy_budget.h says why this much), one value for both backends.
#define GB_ENERGY_BUDGET_TOLERANCE 1e-4
// The energy budget's terms per particle (ParticleEnergy of cpu-reference/energy_budget.h): start, kinetic, held,
// mass, momentum x, y, z, expected momentum x, y, z.
#define GB_ENERGY_TERMS 10
// A closed film's drift terms per particle (driftTerms of cpu-reference/implicit_euler.h): mass, force x, y, z. They
// use the first blocks of the energy budget's tree sum, before the budget does.
#define GB_DRIFT_TERMS 4

// Storage buffer bindings of descriptor set 0. A vector attribute is one buffer holding its x, y and z
// components as three consecutive blocks of `particles` floats (structure of arrays).
#define GB_BINDING_PARAMS 0
#define GB_BINDING_STEPS 1
#define GB_BINDING_POSITION 2
#define GB_BINDING_VELOCITY 3
#define GB_BINDING_FORCE 4
#define GB_BINDING_NORMAL 5
#define GB_BINDING_AIR_INFLOW 6
#define GB_BINDING_AIR_FLOW 7
#define GB_BINDING_AIR_FLOW_NEXT 8
#define GB_BINDING_MASS 9
#define GB_BINDING_LIQUID 10
#define GB_BINDING_VORONOI_AREA 11
#define GB_BINDING_THICKNESS 12
#define GB_BINDING_ELASTICITY 13
#define GB_BINDING_LIFETIME 14
#define GB_BINDING_FRAME_PARAM 15
#define GB_BINDING_ALIVE 16
#define GB_BINDING_TRIANGLES 17
#define GB_BINDING_REST_LENGTH 18
#define GB_BINDING_SPRING_OFFSET 19
#define GB_BINDING_SPRING_INDEX 20
#define GB_BINDING_SPRING_NEIGHBOUR 21
#define GB_BINDING_TRIANGLE_OFFSET 22
#define GB_BINDING_TRIANGLE_CORNER 23  // each particle's triangles as its corners 3 t + c (Topology::triangleCorner)
#define GB_BINDING_BOUNDARY 24
#define GB_BINDING_REDUCE \
  25                            // two halves of `triangles` floats, A then B: the tree sum's ping-pong; then the
                                // coarse correction's patch system (kernels/coarse.glsl)
#define GB_BINDING_DRAINAGE 26  // drainOutflow then drainWeight, `particles` floats each
#define GB_BINDING_TRIANGLE_NORMAL 27
#define GB_BINDING_CORNER_AREA 28
#define GB_BINDING_CONTACTS 29
#define GB_BINDING_PREVIOUS_POSITION 30  // x_t of the implicit step
#define GB_BINDING_COLOUR_ORDER \
  31                         // the implicit solver's lists: its particles colour by colour (M), then
                             // the coarse correction's patchOf (particles), patchOffset (P + 1),
                             // patchMembers (M), patchRowOffset (P + 1), patchRow (kernels/coarse.glsl)
#define GB_BINDING_COUNT 32  // lavapipe's limit of storage buffers per stage: pack before adding
