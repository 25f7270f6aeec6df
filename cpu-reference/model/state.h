#pragma once
// The simulated film as a structure of arrays: one array per attribute, the layout the Vulkan backend
// mirrors with one storage buffer per attribute. float32 throughout (docs/architecture.md).

#include <Eigen/Dense>
#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "kernels/shared/shared_step.h"

namespace gb {

using Vec3 = Eigen::Vector3f;

// A 3-vector per particle stored as three component arrays, so that stages vectorise on the CPU and
// map to three tightly packed float buffers on the GPU.
struct Vec3Array {
  std::vector<float> x, y, z;

  [[nodiscard]] size_t size() const { return x.size(); }
  void resize(size_t n, float value = 0.0f) {
    x.assign(n, value);
    y.assign(n, value);
    z.assign(n, value);
  }
  // n elements, those it had kept: for scratch that is written in full before it is read.
  void fit(size_t n) {
    x.resize(n);
    y.resize(n);
    z.resize(n);
  }
  [[nodiscard]] Vec3 get(size_t i) const { return {x[i], y[i], z[i]}; }
  void set(size_t i, const Vec3& v) {
    x[i] = v.x();
    y[i] = v.y();
    z[i] = v.z();
  }
};

// How a per-particle array of State travels between the host and the Vulkan stepper (kernels/shared/device_data.h).
enum class Transfer {
  ReadBack,    // load() uploads it, store() brings it back
  UploadOnly,  // load() uploads it; the device only reads it, or uses it as scratch
  WithMesh     // uploaded with the mesh: load() and updateTopology()
};

// A per-particle array of `Components` elements a particle: a Vec3Array for three, else a vector.
template <class Element, int Components>
struct ParticleArrayOf {
  using type = std::vector<Element>;
};
template <>
struct ParticleArrayOf<float, 3> {
  using type = Vec3Array;
};
template <class Element, int Components>
using ParticleArray = typename ParticleArrayOf<Element, Components>::type;

// Per-particle state. Indices are stable: a removed particle is flagged dead, never renumbered implicitly.
struct State {
  // One array per line of kernels/shared/device_data.h, named and explained there: the list that the device's buffers,
  // their bindings and their uploads and read-backs follow too (forEachParticleArray).
#define GB_ELEMENT_float float
#define GB_ELEMENT_uint uint32_t
#define GB_BUFFER(binding, NAME, element, declarator, access)
#define GB_PARTICLE_ARRAY(binding, NAME, name, components, element, access, transfer, created) \
  ParticleArray<GB_ELEMENT_##element, components> name;
#define GB_PARTICLE_BLOCK(NAME, block, name, components, transfer, created) ParticleArray<float, components> name;
#include "kernels/shared/device_data.h"
#undef GB_BUFFER
#undef GB_PARTICLE_ARRAY
#undef GB_PARTICLE_BLOCK
#undef GB_ELEMENT_float
#undef GB_ELEMENT_uint
  // Per triangle, written by the geometry stage's first pass and gathered by its second:
  Vec3Array triangleNormal;       // (x1 - x0) x (x2 - x0): twice the area times the unit normal
  std::vector<float> cornerArea;  // mixed Voronoi area of each corner, 3 per triangle

  [[nodiscard]] size_t size() const { return mass.size(); }
  void resize(size_t n);
  // Adds `count` living particles at the end, all attributes zero; existing particles keep their indices
  // and values (film growth, pinch-off caps).
  void append(size_t count);
  // Drops the particles from `first` on (an append undone).
  void removeFrom(size_t first);
};

// Where a per-particle array of State lives on the device and how it travels (its line of device_data.h).
struct ParticleArrayInfo {
  int binding;     // its buffer (gpu::Binding)
  int block;       // its first block of `particles` elements in that buffer
  int components;  // 3 for a Vec3Array (its x, y and z blocks), else 1
  Transfer transfer;
  float created;  // a new particle's value
};

// Calls visit(array, info) for every per-particle array of `state` (a State or a const State), in the order of
// kernels/shared/device_data.h: the one list of them, so that no attribute is left out when the state grows, is
// uploaded, is read back or is saved.
template <class S, class Visit>
void forEachParticleArray(S& state, Visit&& visit) {
#define GB_BUFFER(binding, NAME, element, declarator, access)
#define GB_PARTICLE_ARRAY(binding, NAME, name, components, element, access, transfer, created) \
  visit(state.name, ParticleArrayInfo{binding, 0, components, Transfer::transfer, created});
#define GB_PARTICLE_BLOCK(NAME, block, name, components, transfer, created) \
  visit(state.name, ParticleArrayInfo{gpu::GB_BINDING_##NAME, block, components, Transfer::transfer, created});
#include "kernels/shared/device_data.h"
#undef GB_BUFFER
#undef GB_PARTICLE_ARRAY
#undef GB_PARTICLE_BLOCK
}

// Calls f(component, c) for each float or uint vector of a per-particle array: x, y and z of a Vec3Array (c = 0, 1,
// 2), or the array itself (c = 0).
template <class Array, class F>
void forEachComponent(Array& array, F&& f) {
  if constexpr (requires { array.x; }) {
    f(array.x, 0);
    f(array.y, 1);
    f(array.z, 2);
  } else {
    f(array, 0);
  }
}

// Mean position of the living particles (double accumulation); the origin when none lives.
Vec3 centroid(const State& s);

// Mesh connectivity. Triangles are consistently oriented; springs are the mesh edges. The CSR arrays list,
// for each particle, its springs (with the neighbour at the other end) and its triangles, in a fixed order
// that both backends use for every sum over a one-ring.
struct Topology {
  std::vector<uint32_t> triangles;   // 3 particle indices per triangle, counter-clockwise about the normal
  std::vector<uint32_t> springEnds;  // 2 particle indices per spring
  std::vector<float> restLength;     // l_ij (m)

  std::vector<uint32_t> springOffset;     // CSR: springs of particle i are [springOffset[i], springOffset[i+1])
  std::vector<uint32_t> springIndex;      // spring id
  std::vector<uint32_t> springNeighbour;  // particle at the other end of that spring (the one-ring)
  std::vector<uint32_t> triangleOffset;   // CSR: triangles of particle i
  std::vector<uint32_t> triangleCorner;   // its corner 3 t + c: triangle t = corner / 3, i is its corner c
  std::vector<uint32_t> boundary;         // 1 for a particle held by the wire frame (the "end particles"),
                                          // fixed when the film is made

  [[nodiscard]] size_t triangleCount() const { return triangles.size() / 3; }
  // The three corners of the triangle that `corner` (an entry of triangleCorner) belongs to.
  [[nodiscard]] const uint32_t* triangleOf(uint32_t corner) const { return &triangles[corner - corner % 3]; }
  [[nodiscard]] size_t springCount() const { return restLength.size(); }
  [[nodiscard]] size_t particleCount() const { return boundary.size(); }
  // Whether any particle is held by the wire (boundary): an open film's edge, or a particle pinned.
  [[nodiscard]] bool hasBoundary() const {
    return std::any_of(boundary.begin(), boundary.end(), [](uint32_t b) { return b != 0; });
  }
  // Self-collision candidates of each particle for the current frame, as one packed array (collision.h):
  // contacts[i] .. contacts[i + 1] index the partners stored from contacts[n + 1] on, and after the last
  // partner (from contacts[n + 1 + contacts[n]] on) each pair's rest distance as float bits, in the same order.
  // One array on both backends: the device's 32 bindings are all in use.
  std::vector<uint32_t> contacts;
  // Graph colouring of the particles the implicit solver moves (colouring.h): colour c holds
  // colourOrder[colourOffset[c] .. colourOffset[c + 1]); no two particles joined by a spring or a contact
  // share a colour, so each colour's particles can be solved in parallel in any order.
  std::vector<uint32_t> colourOffset;
  std::vector<uint32_t> colourOrder;
  // Patches of the implicit step's coarse correction (coarse_correction.h): patchOf[i] is particle i's patch
  // (kNoPatch: not solved); patch I holds patchMembers[patchOffset[I] .. patchOffset[I + 1]) in increasing index,
  // and its row of the patch system the patches patchRow[patchRowOffset[I] .. patchRowOffset[I + 1]) in increasing
  // order (itself and those its particles' springs reach).
  std::vector<uint32_t> patchOf, patchOffset, patchMembers, patchRowOffset, patchRow;
  int patchRings = 0;   // the rings the patches were grouped with (Params::coarsePatchRings)
  bool closed = false;  // no edge is used by one triangle only: a bubble. Eqs. (10)-(11)
                        // apply; a burst tears it open again. Set by buildAdjacency.
  [[nodiscard]] bool isClosed() const { return closed; }
};

// The rest distance of the k-th partner entry of a packed contact list for n particles (Topology::contacts): the
// contact penalty pushes the pair apart while it is closer than this.
inline float contactRestDistance(const std::vector<uint32_t>& contacts, size_t n, uint32_t k) {
  return std::bit_cast<float>(contacts[n + 1 + contacts[n] + k]);
}

// An undirected mesh edge (lower < upper particle index) and how many triangles use it: 1 on the film's edge (the
// wire, or a hole's rim), 2 inside it, more where the mesh is not a manifold.
struct EdgeUse {
  uint32_t lower, upper;
  int triangles;
};
// Every edge of `triangles` (indices below particleCount) once, ordered by (lower, upper). A counting sort by
// the lower end: linear in the mesh, where a map of every edge cost 20 ms a frame at 25,650 particles.
std::vector<EdgeUse> edgeUses(size_t particleCount, const std::vector<uint32_t>& triangles);

// Builds springs (one per mesh edge, rest length from the current distance), the CSR one-ring arrays and
// the boundary flags (particles on an edge used by exactly one triangle: the ones the wire holds) from the
// triangle list.
Topology buildTopology(size_t particleCount, std::vector<uint32_t> triangles, const Vec3Array& positions);

// Where each spring of a remade topology comes from (`from`, below): the previous topology's spring whose rest length
// it keeps, or kMadeSpring for a spring made anew.
constexpr uint32_t kMadeSpring = 0xffffffffu;

// The topology of a changed mesh (new particles and triangles stitched to an old film): springs that the
// previous topology had keep their rest length; new springs rest `prestrain` shorter than they are now,
// as at film creation; `from`, if given, gets where each spring comes from (kMadeSpring: made anew). A device that
// holds the rest lengths takes them from it (DeviceResidency::updateMergedRegion).
Topology rebuildTopology(const Topology& previous, std::vector<uint32_t> triangles, const Vec3Array& positions,
                         float prestrain, std::vector<uint32_t>* from = nullptr);

// The topology of a closed mesh after edges collapsed (a free bubble's crowded particles merged): particle i now
// lies at into[i], `triangles` are the surviving ones relabelled, and no two collapsed edges share a triangle. The
// same topology rebuildTopology gives, made from the previous springs instead of from every triangle's edges (at a
// third of the cost, which a merge pays in each of its rounds): a spring whose ends stay keeps its index order and
// rest length, one whose end moved is new unless the survivor had it. A mesh that is open, or whose springs are not
// in (lower, upper) order, is rebuilt. The previous topology's arrays are reused (taken by value: move it in).
Topology collapsedTopology(Topology previous, std::vector<uint32_t> triangles, const std::vector<uint32_t>& into,
                           const Vec3Array& positions, float prestrain, std::vector<uint32_t>* from = nullptr);

// Adds triangles to a mesh in place, without remaking what it had (the film growing a strip at its wire: a remade
// topology cost 25 ms at 100,000 particles, every few frames while the film is drawn). `added` joins particles of the
// mesh's edge and new particles (below particleCount, which the mesh grows to). The springs the mesh had keep their
// index and rest length; each new edge becomes a new spring at the end, `prestrain` shorter than it is now, in
// (lower, upper) order, so that every one-ring lists its springs and triangles in the order buildTopology gives. The
// boundary flags of the particles the triangles touch follow their edges; the contacts are emptied and the colouring
// and patches dropped, as a rebuild does. Throws std::runtime_error, with the mesh unchanged, where an edge would be
// shared by more than two triangles or a triangle names a particle that does not exist.
void appendTriangles(Topology& topology, size_t particleCount, const std::vector<uint32_t>& added,
                     const Vec3Array& positions, float prestrain);

// Rebuilds only the CSR arrays from the triangles and springs, keeping rest lengths and boundary flags
// (a hole torn in the film does not make its rim part of the wire).
void buildAdjacency(Topology& topology);

}  // namespace gb
