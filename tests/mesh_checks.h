#pragma once
// Mesh invariants shared by the tests: orientation, manifoldness, Euler characteristic, CSR consistency.

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <utility>

#include "model/state.h"

namespace gb::test {

// Every directed edge appears at most once (consistent orientation, manifold); returns V - E + F.
inline long eulerCharacteristic(const Topology& topo) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  std::set<std::pair<uint32_t, uint32_t>> undirected;
  std::set<uint32_t> vertices;
  for (size_t t = 0; t < topo.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = topo.triangles[3 * t + c], b = topo.triangles[3 * t + (c + 1) % 3];
      EXPECT_EQ(++directed[std::make_pair(a, b)], 1) << "edge " << a << "->" << b << " used twice in one direction";
      undirected.insert(std::minmax(a, b));
      vertices.insert(a);
    }
  return static_cast<long>(vertices.size()) - static_cast<long>(undirected.size()) +
         static_cast<long>(topo.triangleCount());
}

// The CSR one-ring lists exactly the springs and triangles that touch each particle.
inline void expectAdjacencyMatchesTriangles(const Topology& topo) {
  const size_t n = topo.particleCount();
  std::vector<std::set<uint32_t>> triangles(n), neighbours(n);
  for (uint32_t t = 0; t < topo.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) {
      triangles[topo.triangles[3 * t + c]].insert(t);
      neighbours[topo.triangles[3 * t + c]].insert(topo.triangles[3 * t + (c + 1) % 3]);
      neighbours[topo.triangles[3 * t + (c + 1) % 3]].insert(topo.triangles[3 * t + c]);
    }
  for (size_t i = 0; i < n; ++i) {
    std::set<uint32_t> csrTriangles;
    for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k) {
      EXPECT_EQ(topo.triangles[topo.triangleCorner[k]], i) << "particle " << i << "'s corner " << k;
      csrTriangles.insert(topo.triangleCorner[k] / 3);
    }
    std::set<uint32_t> csrNeighbours(topo.springNeighbour.begin() + topo.springOffset[i],
                                     topo.springNeighbour.begin() + topo.springOffset[i + 1]);
    EXPECT_EQ(csrTriangles, triangles[i]) << "particle " << i;
    EXPECT_EQ(csrNeighbours, neighbours[i]) << "particle " << i;
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
      const uint32_t s = topo.springIndex[k];
      const uint32_t a = topo.springEnds[2 * s], b = topo.springEnds[2 * s + 1];
      EXPECT_TRUE((a == i && b == topo.springNeighbour[k]) || (b == i && a == topo.springNeighbour[k]));
    }
  }
}

}  // namespace gb::test
