// One definition, compiled as C++ (the CPU stages, host/) and GLSL (every compute shader), of what the stages receive
// besides the parameter block: the per-step uniforms, the push constants, the buffer bindings (from the list in
// device_data.h) and the regions of the reduce buffer.
// Vectors are vec4 (w unused) so that std430 and C++ agree without hidden padding; host/ static_asserts
// the offsets and a device test checks them.
#ifdef __cplusplus
#pragma once
#include <cstdint>
namespace gb::gpu {
struct alignas(16) vec4 {
  float x = 0.0f, y = 0.0f, z = 0.0f, w = 0.0f;
};
using uint = uint32_t;
#endif

// What a step needs besides the state, one per step of a submitted batch: computed on the host, read as it is by
// the CPU stages (stages.h calls it StepUniforms) and by the kernels. The vectors are the CPU's WandState and
// WireFrame (cpu-reference/model/wire_frame.h) as vec4; stages.h reads and writes them as those. GB_INIT gives the
// C++ defaults (GLSL has none); a vec4 is zero unless given.
#ifdef __cplusplus
#define GB_INIT(value) = value
#else
#define GB_INIT(value)
#endif
struct StepUniformsBlock {
  vec4 leftPosition;  // wand tips at the start of the step, the air sources of Eq. (5)
  vec4 leftVelocity;
  vec4 rightPosition;
  vec4 rightVelocity;
  vec4 wireCenter;  // the wire frame at the end of the step, for the boundary particles
  vec4 wireAxis GB_INIT(vec4(1.0f, 0.0f, 0.0f, 0.0f));
  vec4 wireDown GB_INIT(vec4(0.0f, -1.0f, 0.0f, 0.0f));
  vec4 volumeOrigin;                     // apex of the cone decomposition of the (swept) volume
  float dt GB_INIT(0.0f);                // substep length (s)
  float leftInflowWeight GB_INIT(1.0f);  // weight of the left source of Eq. (5); the ring's frame has both at its hand
  float airVolume GB_INIT(0.0f);         // V_wm = H_wire * Area_wm, Eq. (6) (m^3)
  float wandAlignment GB_INIT(0.0f);     // MAX(cos theta, 0) of Eq. (5)
  float wireHalfWidth GB_INIT(0.5f);
  float wireDepth GB_INIT(0.5f);
  float referenceVolume GB_INIT(0.0f);  // V_0 of Eq. (11), the volume when the bubble closed (m^3)
  int wireKind GB_INIT(0);              // ToolKind: 0 two wands, 1 ring
  uint closed GB_INIT(0u);              // 1 once the film is a closed bubble: Eqs. (10)-(11) replace Eq. (9)
  // Drainage runs in this step over this time, 0: not in this step. Liquid drains over seconds, so once per frame
  // is enough (Simulation).
  float drainageDt GB_INIT(0.0f);
  float wireArea GB_INIT(0.0f);   // Area_wm (m^2) of Eq. (6): the air flow over it is the air's speed (airCoupling)
  float frameTime GB_INIT(0.0f);  // the frame's length (s): the film checks' impact test (film_checks.h)
  // Implicit integrator: vertex block descent sweeps in this step, 0: Params::solverSweeps (the live loop lowers them
  // when a frame runs over its budget). The host records the sweeps; no kernel reads it.
  int solverSweeps GB_INIT(0);
};
#undef GB_INIT

// Push constants of every stage (36 bytes of the 128 guaranteed).
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
  float ruleShare;       // film_rest_lengths with GB_RULE_CONTRACT: the share of the way each spring contracts
};

#ifdef __cplusplus
}  // namespace gb::gpu
#endif

// PushBlock::reduceFlags, one meaning per bit in every kernel. A tree sum ping-pongs between the halves A and B of
// its region; a flag says which half holds what a kernel reads (a level's input, or a finished sum).
#define GB_REDUCE_VOLUME_IN_A 1u       // the volume's tree sum: half A holds it (else half B)
#define GB_REDUCE_ENERGY_IN_A 2u       // the energy terms' tree sum: half A holds it (else half B)
#define GB_REDUCE_AT_STEP_START 4u     // triangle_volume: the volume at the step's start (the energy budget's)
#define GB_REDUCE_DRIFT_ONLY 8u        // energy_tree_sum: only external_drift's first GB_DRIFT_TERMS blocks
#define GB_REDUCE_STATISTICS_IN_A 32u  // film_statistics_tree: half A holds the level it reads (else half B)
#define GB_RULE_YIELD 64u              // film_rest_lengths: the yield of stretched springs
#define GB_RULE_PAYOUT 128u            // film_rest_lengths: the wire's payout
#define GB_RULE_CONTRACT 1024u         // film_rest_lengths: the contraction of slack springs, PushBlock::ruleShare
#define GB_REACH_FASTEST 256u          // contact_reach: the runs' fastest speeds (its second pass; else their sums)
#define GB_REACH_FINAL 512u            // contact_reach: the reach from the runs' fastest speeds (its third pass)

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
//   coarse blocks   the coarse correction's 3x3 blocks, 9 R, column-major (kernels/step/coarse.glsl);
//   coarse vectors  its right-hand side, solution, residual, direction, preconditioned, product (3 P each, x, y and
//                   z blocks of P), the patches' shortest springs (P), its dot products' halves A and B (P each);
//   energy terms    the energy budget's terms, halves A and B of GB_ENERGY_TERMS blocks of N floats;
//   energy slots    the bubble's volume before the step, then the VelocityBudget (GB_SLOT_*);
//   statistics      the frame's statistics terms (GB_STAT_*), halves A and B of GB_STATISTICS_TERMS blocks of N.
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
// The frame's statistics on the device (film_statistics_terms, film_statistics_tree; FrameStats of
// cpu-reference/simulation/simulation.h) and the film checks of the rules between steps (FilmChecks of
// cpu-reference/topology/film_checks.h): each particle's terms, then their sums over the film, except the largest
// kept (GB_STAT_KEEPS_LARGEST): the speed and the checks' extremes, a least value kept as its negative.
#define GB_STAT_PARTICLES 0  // 1 for a living particle
#define GB_STAT_KINETIC 1    // 1/2 m v^2 (J)
#define GB_STAT_POTENTIAL 2  // the liquid's potential energy in gravity, -rho w g . x (J)
#define GB_STAT_LIQUID 3     // w (m^3)
#define GB_STAT_THICKNESS 4  // e (m), summed for the mean
#define GB_STAT_AIR_FLOW 5   // |air flow| (m^3/s), summed for the mean
#define GB_STAT_ELASTIC 6    // half of each spring's energy (Eq. 3), or the film tension's energy (tensionModel 1) (J)
#define GB_STAT_AREA 7       // a third of each of its triangles' area (m^2)
#define GB_STAT_VOLUME 8     // a third of each of its triangles' cone volume to the frame's origin (m^3)
#define GB_STAT_SPEED 9      // |v| (m/s): the largest is kept
#define GB_STAT_WINDING_LEFT 10           // a third of each of its triangles' solid angle about the left tip over 4 pi
#define GB_STAT_WINDING_RIGHT 11          // the same about the right tip
#define GB_STAT_YIELDING 12               // half of each of its springs the yield rule would lengthen
#define GB_STAT_SLACK 13                  // half of each of its springs the contraction would take
#define GB_STAT_CROWDED 14                // half of each of its slack springs with a thick end
#define GB_STAT_RUNGS_PAST_GROWTH 15      // half of each of its rungs past growthStretch
#define GB_STAT_WIRE_EDGES 16             // half the length of each of its springs along the wire (m)
#define GB_STAT_WIRE_EDGE_COUNT 17        // half of each of its springs along the wire
#define GB_STAT_RUNG_REST 18              // half the rest length of each of its rungs (m)
#define GB_STAT_RUNG_COUNT 19             // half of each of its rungs
#define GB_STAT_CONTRACTION_QUADRATIC 20  // half of contractionQuadraticOf of each of its springs the contraction takes
#define GB_STAT_CONTRACTION_LINEAR 21     // half of contractionLinearOf of each of them
#define GB_STAT_UNSTABLE 22    // 1 for a living particle not finite or faster than kUnstableSpeed: largest kept
#define GB_STAT_DEPTH 23       // -y of a living particle (m): largest kept, the lowest particle
#define GB_STAT_NEAR_LEFT 24   // -|x - left tip| of a living particle (m): largest kept, the nearest
#define GB_STAT_NEAR_RIGHT 25  // -|x - right tip| (m): largest kept
#define GB_STAT_THIN 26        // -e of a living particle with area (m): largest kept, the thinnest
#define GB_STAT_IMPACT 27      // impact number of its hardest contact closing within the frame: largest kept
#define GB_STATISTICS_TERMS 28
#define GB_STAT_KEEPS_LARGEST(c) ((c) == GB_STAT_SPEED || (c) >= GB_STAT_UNSTABLE)

// Between frames the statistics region also holds the merges' work: what crowded_springs finds (the median squared
// spring length, the living springs, the springs listed, then the list: spring numbers as floats, exact below 2^24
// springs), or what rest_length_gather reads (where each spring of the new mesh comes from, as floats, negative for a
// spring made anew; then the rest lengths of the mesh before).
#define GB_CROWDED_MEDIAN 0
#define GB_CROWDED_LIVING 1
#define GB_CROWDED_LISTED 2
#define GB_CROWDED_LIST 3
#ifdef __cplusplus
namespace gb::gpu {
#define GB_REGION inline constexpr
GB_REGION uint maxOf(uint a, uint b) { return a > b ? a : b; }
#else
#define GB_REGION
uint maxOf(uint a, uint b) { return max(a, b); }
#endif
// The tree sums (tree_sum, energy_tree_sum, film_statistics_tree) take GB_TREE_PASS_LEVELS levels of treeSum in one
// pass, a workgroup summing 2^levels consecutive values (tree_pass.glsl): a dispatch and a barrier a pass instead of a
// level (a volume's 15 levels in 2 passes), which on a real GPU are a large part of a small film's step. A pass over
// n values leaves treePassOutputs(n).
#define GB_TREE_PASS_LEVELS 8u
GB_REGION uint treePassOutputs(uint n) { return (n + (1u << GB_TREE_PASS_LEVELS) - 1u) >> GB_TREE_PASS_LEVELS; }
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
GB_REGION uint reduceStatisticsAt(uint energyTermsAt, uint particleCount) {
  return reduceEnergySlotsAt(energyTermsAt, particleCount) + uint(GB_ENERGY_SLOTS);
}
GB_REGION uint reduceFloatsWith(uint energyTermsAt, uint particleCount) {
  return reduceStatisticsAt(energyTermsAt, particleCount) + 2u * uint(GB_STATISTICS_TERMS) * maxOf(particleCount, 1u);
}
#undef GB_REGION
#ifdef __cplusplus
}  // namespace gb::gpu
#endif

// The device contact search (kernels/contacts/contact_*.comp, host/vulkan_contact_search.cpp). The contacts buffer
// (GB_BINDING_CONTACTS) holds the packed list Topology::contacts from 0, with room for C partner entries: N + 1
// offsets, C partners, C rest distances. The search's regions follow, from its header at contactSearchAt(N, C) on
// (uints), with B buckets (a power of two) and room for K partners a particle:
//   header         GB_CONTACT_HEADER slots (GB_CONTACT_*), set by the host before each search and by the kernels;
//   bucket starts  B + 1: each bucket's particle count, then (scanned) where its particles start in `sorted`;
//   bucket of      N: each particle's bucket, GB_NO_BUCKET for one not searched (dead, torn out, not finite);
//   slot           N: its place among its bucket's particles;
//   sorted         N: the searched particles, bucket by bucket;
//   rows           N K: each particle's partners, ascending (the first K of them);
//   scan totals    the block sums of the scans (contact_scan_*), one per GB_SCAN_RUN elements at most;
//   sheets         B GB_CONTACT_SHEET floats: each bucket's particles as a piece of sheet (contact_sheets), and
//                  before them contact_reach's partial results (contactReachGroups);
//   previous       the last list, packed as the list is, for the pairs' rest distances.
// The kernels get the header's start in PushBlock::first and read B and K from it.
#define GB_CONTACT_REACH 0               // the search's reach (float bits): no pair lies farther apart
#define GB_CONTACT_MOST_PARTNERS 1       // the most partners one particle has (K or less, or the rows overflowed)
#define GB_CONTACT_PARTNER_ENTRIES 2     // all partners of all particles: C or less, or the list overflowed
#define GB_CONTACT_PREVIOUS_PARTICLES 3  // the previous list's particle count N', 0 when there is none
#define GB_CONTACT_ROW_CAPACITY 4        // K
#define GB_CONTACT_ENTRY_CAPACITY 5      // C
#define GB_CONTACT_BUCKETS 6             // B
#define GB_CONTACT_FRAME_TIME 7          // the frame the pairs may close over (float bits, s)
#define GB_CONTACT_SLACK 8               // what the frame's forces may add to it (float bits, m)
#define GB_CONTACT_HEADER 9
#define GB_NO_BUCKET 0xffffffffu
// A bucket's sheet (BucketSheet of cpu-reference/topology/collision.cpp): its box's lower and upper corners, its
// mean normal, the spread of its normals about it, and its particles' heights along it (lowest, highest).
#define GB_SHEET_LOWER 0
#define GB_SHEET_UPPER 3
#define GB_SHEET_NORMAL 6
#define GB_SHEET_SPREAD 9
#define GB_SHEET_HEIGHTS 10
#define GB_CONTACT_SHEET 12
#define GB_SCAN_RUN 16u   // elements one invocation of contact_scan_blocks adds in a row
#define GB_SCAN_ROWS 16u  // PushBlock::reduceFlags of contact_scan_*: the partner counts (else the bucket counts)
#define GB_REACH_RUN 16u  // particles one invocation of contact_reach reads in each of its passes

#ifdef __cplusplus
namespace gb::gpu {
#endif
struct ContactSearchLayout {
  uint header, bucketStart, bucketOf, slot, sorted, rows, scanTotals, sheets, previous;
};
#ifdef __cplusplus
#define GB_REGION inline constexpr
#else
#define GB_REGION
#endif
GB_REGION uint contactSearchAt(uint particleCount, uint entryCapacity) {
  return particleCount + 1u + 2u * entryCapacity;
}
// The scans' block sums: at most one per GB_SCAN_RUN elements of the longer of the two arrays scanned.
GB_REGION uint contactScanTotals(uint particleCount, uint buckets) {
  return (maxOf(particleCount, buckets) + 1u + GB_SCAN_RUN - 1u) / GB_SCAN_RUN;
}
// The workgroups of contact_reach's first two passes: one per GB_REACH_RUN particles an invocation. Their partial
// results lie at the start of the sheets region (4 floats a workgroup, then 1), which contact_sheets fills later.
GB_REGION uint contactReachGroups(uint particleCount, uint workgroupSize) {
  return maxOf(1u, (particleCount + workgroupSize * GB_REACH_RUN - 1u) / (workgroupSize * GB_REACH_RUN));
}
GB_REGION ContactSearchLayout contactSearchLayout(uint header, uint particleCount, uint buckets, uint rowCapacity) {
  ContactSearchLayout l;
  l.header = header;
  l.bucketStart = header + uint(GB_CONTACT_HEADER);
  l.bucketOf = l.bucketStart + buckets + 1u;
  l.slot = l.bucketOf + particleCount;
  l.sorted = l.slot + particleCount;
  l.rows = l.sorted + particleCount;
  l.scanTotals = l.rows + particleCount * rowCapacity;
  l.sheets = l.scanTotals + contactScanTotals(particleCount, buckets);
  l.previous = l.sheets + uint(GB_CONTACT_SHEET) * buckets;
  return l;
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
