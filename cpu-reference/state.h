#pragma once
// The simulated film as a structure of arrays: one array per attribute, the layout the Vulkan backend
// mirrors with one storage buffer per attribute. float32 throughout (ARCHITECTURE.md).

#include <Eigen/Dense>
#include <bit>
#include <cstdint>
#include <vector>

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
  [[nodiscard]] Vec3 get(size_t i) const { return {x[i], y[i], z[i]}; }
  void set(size_t i, const Vec3& v) {
    x[i] = v.x();
    y[i] = v.y();
    z[i] = v.z();
  }
};

// Per-particle state. Indices are stable: a removed particle is flagged dead, never renumbered implicitly.
struct State {
  Vec3Array position;               // x_i (m)
  Vec3Array velocity;               // v_i (m/s)
  Vec3Array force;                  // total force of Eq. (2) of the last step (N)
  Vec3Array normal;                 // unit vertex normal n_i
  Vec3Array airInflow;              // direct air inflow of Eq. (5) (m^3/s)
  Vec3Array airFlow;                // transferred air flow of Eqs. (7)-(8) (m^3/s), Jacobi front buffer
  Vec3Array airFlowNext;            // Jacobi back buffer of the air transfer
  Vec3Array previousPosition;       // x_t, the position at the start of an implicit step (implicit_euler.h)
  std::vector<float> mass;          // m_i (kg), fixed at creation from the film inertia
  std::vector<float> liquid;        // liquid volume carried by the particle (m^3); w_e of Section 5.1
  std::vector<float> voronoiArea;   // mixed Voronoi area A_Vor(p_i) (m^2)
  std::vector<float> thickness;     // e_i = liquid / A_Vor (m)
  std::vector<float> elasticity;    // E_i of Eq. (4) (N/m)
  std::vector<float> lifetime;      // time since the particle was created (s)
  std::vector<float> drainOutflow;  // liquid particle i sends downhill this step (m^3), drainage pass 1
  std::vector<float> drainWeight;   // sum of d_dir of Eq. (14) over i's neighbours, drainage pass 1
  std::vector<float> frameParam;    // wire-frame coordinate of a boundary particle (see wire_frame.h); negative:
                                    // the particle is pinned where it is (fixed rings, film_shapes.h)
  std::vector<uint32_t> alive;      // 1 while the particle exists (uint32: the GPU reads it as a uint)
  // Per triangle, written by the geometry stage's first pass and gathered by its second:
  Vec3Array triangleNormal;       // (x1 - x0) x (x2 - x0): twice the area times the unit normal
  std::vector<float> cornerArea;  // mixed Voronoi area of each corner, 3 per triangle

  [[nodiscard]] size_t size() const { return mass.size(); }
  void resize(size_t n);
  // Adds `count` living particles at the end, all attributes zero; existing particles keep their indices
  // and values (film growth, pinch-off caps).
  void append(size_t count);
};

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

// The topology of a changed mesh (new particles and triangles stitched to an old film): springs that the
// previous topology had keep their rest length; new springs rest `prestrain` shorter than they are now,
// as at film creation; `made`, if given, gets the new springs' indices.
Topology rebuildTopology(const Topology& previous, std::vector<uint32_t> triangles, const Vec3Array& positions,
                         float prestrain, std::vector<size_t>* made = nullptr);

// Rebuilds only the CSR arrays from the triangles and springs, keeping rest lengths and boundary flags
// (a hole torn in the film does not make its rim part of the wire).
void buildAdjacency(Topology& topology);

}  // namespace gb
