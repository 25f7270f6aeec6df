#include "solver/coarse_correction.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include "solver/colouring.h"
#include "solver/energy_budget.h"

namespace gb {

namespace {

// A patch moves at most half the shortest spring of its particles: kPatchTrustScale times a particle's trust region
// (shared_formulas.h). At a particle's quarter spring the correction was cut short on a film bulged by 5 cm (21.8% of
// the step's pull-back left undone against 17.3%, coarse_correction_test); at a whole spring the physical model's
// 9,500-particle stress run gained 3.24% over a rest (frame 1,099), at half a spring at most 0.62%.

// Breadth first from seed over solver particles that no patch holds yet, up to `rings` springs away.
void growPatch(const std::vector<uint32_t>& alive, const Topology& topo, uint32_t seed, uint32_t patch, int rings,
               std::vector<uint32_t>& patchOf) {
  std::deque<std::pair<uint32_t, int>> frontier{{seed, 0}};
  patchOf[seed] = patch;
  while (!frontier.empty()) {
    const auto [i, ring] = frontier.front();
    frontier.pop_front();
    if (ring == rings) continue;
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
      const uint32_t j = topo.springNeighbour[k];
      if (patchOf[j] != kNoPatch || !isSolverParticle(alive, topo, j)) continue;
      patchOf[j] = patch;
      frontier.emplace_back(j, ring + 1);
    }
  }
}

// The neighbouring patch a small patch shares the most springs with (the lowest such index on a tie), or
// kNoPatch when it has none.
uint32_t bestNeighbour(const Topology& topo, const std::vector<uint32_t>& members, uint32_t patch,
                       const std::vector<uint32_t>& patchOf) {
  std::vector<std::pair<uint32_t, int>> shared;  // (patch, springs)
  for (uint32_t i : members)
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
      const uint32_t other = patchOf[topo.springNeighbour[k]];
      if (other == kNoPatch || other == patch) continue;
      auto it = std::find_if(shared.begin(), shared.end(), [&](const auto& e) { return e.first == other; });
      if (it == shared.end())
        shared.emplace_back(other, 1);
      else
        ++it->second;
    }
  uint32_t best = kNoPatch;
  int most = 0;
  for (const auto& [other, springs] : shared)
    if (springs > most || (springs == most && other < best)) best = other, most = springs;
  return best;
}

// Numbers the patches 0, 1, ... in the order of their lowest particle and lays out their member and row lists.
void layOutPatches(Topology& topo) {
  const size_t n = topo.particleCount();
  std::vector<uint32_t> renumber(n, kNoPatch);
  uint32_t patches = 0;
  for (size_t i = 0; i < n; ++i) {
    uint32_t& p = topo.patchOf[i];
    if (p == kNoPatch) continue;
    if (renumber[p] == kNoPatch) renumber[p] = patches++;
    p = renumber[p];
  }
  topo.patchOffset.assign(patches + 1, 0u);
  for (size_t i = 0; i < n; ++i)
    if (topo.patchOf[i] != kNoPatch) ++topo.patchOffset[topo.patchOf[i] + 1];
  for (uint32_t p = 0; p < patches; ++p) topo.patchOffset[p + 1] += topo.patchOffset[p];
  topo.patchMembers.assign(topo.patchOffset.back(), 0u);
  std::vector<uint32_t> fill(topo.patchOffset.begin(), topo.patchOffset.end() - 1);
  for (size_t i = 0; i < n; ++i)
    if (topo.patchOf[i] != kNoPatch) topo.patchMembers[fill[topo.patchOf[i]]++] = static_cast<uint32_t>(i);
  topo.patchRowOffset.assign(1, 0u);
  topo.patchRow.clear();
  std::vector<uint32_t> row;
  for (uint32_t p = 0; p < patches; ++p) {
    row.assign(1, p);
    for (uint32_t m = topo.patchOffset[p]; m < topo.patchOffset[p + 1]; ++m) {
      const uint32_t i = topo.patchMembers[m];
      for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k)
        if (const uint32_t other = topo.patchOf[topo.springNeighbour[k]]; other != kNoPatch) row.push_back(other);
    }
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    topo.patchRow.insert(topo.patchRow.end(), row.begin(), row.end());
    topo.patchRowOffset.push_back(static_cast<uint32_t>(topo.patchRow.size()));
  }
}

// The slot of patch `column` in patch `row`'s row of the patch system.
uint32_t rowSlot(const Topology& topo, uint32_t row, uint32_t column) {
  const auto first = topo.patchRow.begin() + topo.patchRowOffset[row],
             last = topo.patchRow.begin() + topo.patchRowOffset[row + 1];
  return static_cast<uint32_t>(std::lower_bound(first, last, column) - topo.patchRow.begin());
}

}  // namespace

int coarseSweepsBefore(const Params& p, const StepUniforms& u) {
  return p.coarseIterations > 0 ? sweepsThisStep(p, u) / 2 : -1;
}

void groupIntoPatches(const std::vector<uint32_t>& alive, int rings, Topology& topo) {
  const size_t n = topo.particleCount();
  topo.patchOf.assign(n, kNoPatch);
  uint32_t patches = 0;
  for (size_t i = 0; i < n; ++i)
    if (topo.patchOf[i] == kNoPatch && isSolverParticle(alive, topo, i))
      growPatch(alive, topo, static_cast<uint32_t>(i), patches++, rings, topo.patchOf);
  // Patches squeezed between full ones join a neighbour: they would add unknowns that hardly reach further
  // than a sweep does. A full patch on a triangle mesh holds 1 + 3 r (r + 1) particles.
  std::vector<std::vector<uint32_t>> members(patches);
  for (size_t i = 0; i < n; ++i)
    if (topo.patchOf[i] != kNoPatch) members[topo.patchOf[i]].push_back(static_cast<uint32_t>(i));
  const size_t full = 1 + 3 * static_cast<size_t>(rings) * static_cast<size_t>(rings + 1);
  for (uint32_t p = 0; p < patches; ++p) {
    if (members[p].empty() || 3 * members[p].size() >= full) continue;
    const uint32_t into = bestNeighbour(topo, members[p], p, topo.patchOf);
    if (into == kNoPatch) continue;
    for (uint32_t i : members[p]) topo.patchOf[i] = into;
    members[into].insert(members[into].end(), members[p].begin(), members[p].end());
    members[p].clear();
  }
  layOutPatches(topo);
  topo.patchRings = rings;
}

void ensurePatches(const std::vector<uint32_t>& alive, int rings, Topology& topo) {
  if (topo.patchOffset.empty() || topo.patchRings != rings) groupIntoPatches(alive, rings, topo);
}

Eigen::Matrix3f springCouplingBlock(const Params& p, float h, const Topology& topo, const State& s, const Vec3Array& x,
                                    size_t i, uint32_t k) {
  const uint32_t j = topo.springNeighbour[k];
  const Vec3 d = x.get(j) - x.get(i);
  const float len = d.norm();
  if (!(len > 0)) return Eigen::Matrix3f::Zero();
  const Vec3 dir = d / len;
  float along = p.springDamping / h, transverse = 0.0f;
  if (p.tensionModel != 1) {
    const float stiffness = springStiffness(s, i, j);
    transverse = transverseStiffness(stiffness, topo.restLength[topo.springIndex[k]], len);
    along += stiffness - transverse;
  }
  return -(along * dir * dir.transpose() + transverse * Eigen::Matrix3f::Identity());
}

Eigen::Matrix3f triangleCouplingBlock(const Params& p, const Topology& topo, const State& s, const Vec3Array& x,
                                      const uint32_t* tri, uint32_t c, uint32_t l) {
  // Gauss-Newton Hessian of T |n| / 2, n = (x1 - x0) x (x2 - x0): T / (2 |n|) J_c^T (I - n n^T / |n|^2) J_l with
  // J_l v = e_l x v, e_l = x_{l+2} - x_{l+1} the edge facing corner l. J_c^T P J_l = -[e_c]x P [e_l]x, and
  // [a]x (I - n n^T) [b]x = b a^T - (a . b) I + (a x n)(b x n)^T for a unit n: two outer products instead of two
  // 3x3 products.
  const Vec3 x0 = x.get(tri[0]), x1 = x.get(tri[1]), x2 = x.get(tri[2]);
  const Vec3 normal = (x1 - x0).cross(x2 - x0);
  const float twiceArea = normal.norm();
  if (!(twiceArea > 0)) return Eigen::Matrix3f::Zero();
  const Vec3 edges[3] = {x2 - x1, x0 - x2, x1 - x0}, n = normal / twiceArea;
  const Vec3 a = edges[c], b = edges[l];
  const Eigen::Matrix3f sandwich =
      b * a.transpose() - a.dot(b) * Eigen::Matrix3f::Identity() + a.cross(n) * b.cross(n).transpose();
  // The tension at the triangle's current area (Gibbs's law, triangleTensionAt), and the law's own term
  // dT/dA grad_c A grad_l A^T with grad_c A = n x e_c / 2.
  const float area = 0.5f * twiceArea, startTension = triangleTension(s, tri),
              startArea = triangleAreaAtStart(topo, s, tri);
  const float tension = triangleTensionAt(p, startTension, startArea, area);
  const float slope = triangleTensionSlope(p, startTension, startArea, area);
  return -(tension / (2.0f * twiceArea)) * sandwich + (0.25f * slope) * (a.cross(n) * b.cross(n).transpose());
}

void fitCoarseSystem(const Topology& topo, CoarseSystem& system) {
  const size_t patches = topo.patchOffset.empty() ? 0 : topo.patchOffset.size() - 1;
  system.blocks.resize(topo.patchRow.size());
  system.shortestSpring.resize(patches);
  for (Vec3Array* a : {&system.rightHandSide, &system.solution, &system.residual, &system.direction,
                       &system.preconditioned, &system.product})
    a->resize(patches);
}

void coarseAssemble(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo, const State& s,
                    size_t patch, CoarseSystem& system) {
  const auto row = static_cast<uint32_t>(patch);
  for (uint32_t slot = topo.patchRowOffset[row]; slot < topo.patchRowOffset[row + 1]; ++slot)
    system.blocks[slot].setZero();
  const uint32_t diagonal = rowSlot(topo, row, row);
  Vec3 rightHandSide = Vec3::Zero();
  float shortest = std::numeric_limits<float>::infinity();
  for (uint32_t m = topo.patchOffset[row]; m < topo.patchOffset[row + 1]; ++m) {
    const uint32_t i = topo.patchMembers[m];
    if (!s.alive[i]) continue;  // died in a burst since the patches were made
    const VertexBlock b = objectiveBlock(p, u, bubble, topo, s, i);
    system.blocks[diagonal] += b.hessian;
    rightHandSide -= b.gradient;
    shortest = std::min(shortest, b.shortestSpring);
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
      const uint32_t other = topo.patchOf[topo.springNeighbour[k]];
      if (other == kNoPatch) continue;
      system.blocks[rowSlot(topo, row, other)] += springCouplingBlock(p, u.dt, topo, s, s.position, i, k);
    }
    if (p.tensionModel != 1) continue;
    for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k) {
      const uint32_t corner = topo.triangleCorner[k], c = corner % 3;
      const uint32_t* tri = topo.triangleOf(corner);
      for (uint32_t l = 0; l < 3; ++l) {
        const uint32_t other = topo.patchOf[tri[l]];
        if (l == c || other == kNoPatch) continue;
        system.blocks[rowSlot(topo, row, other)] += triangleCouplingBlock(p, topo, s, s.position, tri, c, l);
      }
    }
  }
  system.rightHandSide.set(patch, rightHandSide);
  system.shortestSpring[patch] = shortest;
}

namespace {

// out = A v over the patch system's rows.
void coarseProduct(const Topology& topo, const CoarseSystem& system, const Vec3Array& v, Vec3Array& out) {
  for (uint32_t row = 0; row + 1 < topo.patchRowOffset.size(); ++row) {
    Vec3 sum = Vec3::Zero();
    for (uint32_t slot = topo.patchRowOffset[row]; slot < topo.patchRowOffset[row + 1]; ++slot)
      sum += system.blocks[slot] * v.get(topo.patchRow[slot]);
    out.set(row, sum);
  }
}

// sum over the patches of a . b, as a tree sum.
float coarseDot(const Vec3Array& a, const Vec3Array& b) {
  std::vector<float> terms(a.size());
  for (size_t k = 0; k < terms.size(); ++k) terms[k] = a.get(k).dot(b.get(k));
  return treeSum(std::move(terms));
}

void precondition(const Topology& topo, CoarseSystem& system) {
  for (uint32_t row = 0; row + 1 < topo.patchRowOffset.size(); ++row)
    system.preconditioned.set(row, solveLinear3(system.blocks[rowSlot(topo, row, row)], system.residual.get(row)));
}

}  // namespace

void coarseSolve(const Topology& topo, int iterations, CoarseSystem& system) {
  const size_t patches = system.rightHandSide.size();
  system.solution.resize(patches);
  system.residual = system.rightHandSide;
  precondition(topo, system);
  system.direction = system.preconditioned;
  float residualDot = coarseDot(system.residual, system.preconditioned);
  for (int it = 0; it < iterations; ++it) {
    coarseProduct(topo, system, system.direction, system.product);
    const float curvature = coarseDot(system.direction, system.product);
    if (!(curvature > 0.0f) || !(residualDot > 0.0f)) break;
    const float alpha = residualDot / curvature;
    for (size_t k = 0; k < patches; ++k) {
      system.solution.set(k, system.solution.get(k) + alpha * system.direction.get(k));
      system.residual.set(k, system.residual.get(k) - alpha * system.product.get(k));
    }
    precondition(topo, system);
    const float next = coarseDot(system.residual, system.preconditioned);
    const float beta = next / residualDot;
    residualDot = next;
    for (size_t k = 0; k < patches; ++k)
      system.direction.set(k, system.preconditioned.get(k) + beta * system.direction.get(k));
  }
}

void coarseApply(const Topology& topo, const CoarseSystem& system, State& s, size_t i) {
  const uint32_t patch = topo.patchOf[i];
  if (patch == kNoPatch || !s.alive[i]) return;
  const Vec3 move = withinTrustRegion(system.solution.get(patch), kPatchTrustScale * system.shortestSpring[patch]);
  if (!move.allFinite()) return;
  s.position.set(i, aboveFloor(s.position.get(i) + move));
}

}  // namespace gb
