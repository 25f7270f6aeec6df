// The mesh's topology: springs, one-rings and boundary flags made from triangles (state.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "model/state.h"
#include "solver/coarse_correction.h"
#include "solver/colouring.h"

namespace gb {
namespace {

// A strip of `rows` x `columns` particles, row r at height r with a little depth so no two edges have one length,
// and the triangles between rows [from, to): a band of film, open at both ends.
struct Grid {
  size_t rows, columns;
  [[nodiscard]] uint32_t at(size_t r, size_t c) const { return static_cast<uint32_t>(r * columns + c); }
  [[nodiscard]] Vec3Array positions() const {
    Vec3Array x;
    x.resize(rows * columns);
    for (size_t r = 0; r < rows; ++r)
      for (size_t c = 0; c < columns; ++c)
        x.set(at(r, c), Vec3(static_cast<float>(c), static_cast<float>(r), 0.1f * std::sin(float(r * 7 + c * 3))));
    return x;
  }
  [[nodiscard]] std::vector<uint32_t> triangles(size_t from, size_t to) const {
    std::vector<uint32_t> t;
    for (size_t r = from; r < to; ++r)
      for (size_t c = 0; c + 1 < columns; ++c)
        t.insert(t.end(), {at(r, c), at(r, c + 1), at(r + 1, c), at(r, c + 1), at(r + 1, c + 1), at(r + 1, c)});
    return t;
  }
};

std::vector<uint32_t> row(const std::vector<uint32_t>& offset, const std::vector<uint32_t>& entries, size_t i) {
  return {entries.begin() + offset[i], entries.begin() + offset[i + 1]};
}

TEST(Topology, TrianglesAppendedAtTheEdgeGiveTheOneRingsARebuildGivesAndKeepTheOldSprings) {
  const Grid grid{7, 9};
  const Vec3Array x = grid.positions();
  const size_t oldParticles = 3 * grid.columns;  // rows 0-2; the appended bands reach rows 3-6
  Topology topo = buildTopology(oldParticles, grid.triangles(0, 2), x);
  for (size_t k = 0; k < topo.springCount(); ++k) topo.restLength[k] = 100.0f + static_cast<float>(k);
  const Topology before = topo;
  constexpr float prestrain = 0.1f;
  appendTriangles(topo, x.size(), grid.triangles(2, 6), x, prestrain);
  const Topology rebuilt = buildTopology(x.size(), grid.triangles(0, 6), x);

  EXPECT_EQ(topo.triangles, rebuilt.triangles);
  EXPECT_EQ(topo.boundary, rebuilt.boundary);  // rows 0 and 6 and the two ends; row 2 is inside now
  EXPECT_FALSE(topo.closed);
  ASSERT_EQ(topo.springCount(), rebuilt.springCount());
  for (size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(row(topo.springOffset, topo.springNeighbour, i), row(rebuilt.springOffset, rebuilt.springNeighbour, i))
        << "particle " << i;
    EXPECT_EQ(row(topo.triangleOffset, topo.triangleCorner, i), row(rebuilt.triangleOffset, rebuilt.triangleCorner, i))
        << "particle " << i;
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {  // each entry names its spring
      const uint32_t s = topo.springIndex[k], j = topo.springNeighbour[k];
      const uint32_t a = topo.springEnds[2 * s], b = topo.springEnds[2 * s + 1];
      EXPECT_TRUE((a == i && b == j) || (a == j && b == i)) << "particle " << i << ", spring " << s;
    }
  }
  for (size_t k = 0; k < before.springCount(); ++k) {  // the old springs: same index, ends and rest length
    EXPECT_EQ(topo.springEnds[2 * k], before.springEnds[2 * k]);
    EXPECT_EQ(topo.springEnds[2 * k + 1], before.springEnds[2 * k + 1]);
    EXPECT_EQ(topo.restLength[k], before.restLength[k]);
  }
  for (size_t k = before.springCount(); k < topo.springCount(); ++k) {  // the new: prestrained at their length
    const float length = (x.get(topo.springEnds[2 * k]) - x.get(topo.springEnds[2 * k + 1])).norm();
    EXPECT_FLOAT_EQ(topo.restLength[k], length * (1.0f - prestrain));  // one multiplication's rounding
  }
  EXPECT_TRUE(topo.colourOrder.empty());
  EXPECT_EQ(topo.contacts, std::vector<uint32_t>(x.size() + 1, 0u));
}

TEST(Topology, ATriangleOnAnEdgeTwoTrianglesShareIsRefusedAndTheMeshStays) {
  const Grid grid{4, 5};
  const Vec3Array x = grid.positions();
  Topology topo = buildTopology(x.size(), grid.triangles(0, 3), x);
  const Topology before = topo;
  // Row 1's first edge lies between bands 0 and 1: a third triangle on it is not a manifold.
  const std::vector<uint32_t> third = {grid.at(1, 0), grid.at(1, 1), grid.at(3, 4)};
  EXPECT_THROW(appendTriangles(topo, x.size(), third, x, 0.0f), std::runtime_error);
  EXPECT_EQ(topo.triangles, before.triangles);
  EXPECT_EQ(topo.springEnds, before.springEnds);
  EXPECT_EQ(topo.springOffset, before.springOffset);
  EXPECT_EQ(topo.boundary, before.boundary);
  EXPECT_THROW(appendTriangles(topo, x.size(), {grid.at(3, 3), grid.at(3, 4), 999u}, x, 0.0f), std::runtime_error);
  EXPECT_THROW(appendTriangles(topo, x.size(), {grid.at(3, 3), grid.at(3, 4)}, x, 0.0f), std::runtime_error);
  EXPECT_EQ(topo.triangles, before.triangles);
}

// A torus of `rows` x `columns` particles (both directions wrap round): a closed mesh.
std::vector<uint32_t> torusTriangles(const Grid& grid) {
  std::vector<uint32_t> t;
  const auto at = [&](size_t r, size_t c) { return grid.at(r % grid.rows, c % grid.columns); };
  for (size_t r = 0; r < grid.rows; ++r)
    for (size_t c = 0; c < grid.columns; ++c)
      t.insert(t.end(), {at(r, c), at(r, c + 1), at(r + 1, c), at(r, c + 1), at(r + 1, c + 1), at(r + 1, c)});
  return t;
}

TEST(Topology, CollapsedEdgesGiveTheTopologyARebuildGives) {
  const Grid grid{12, 16};
  const Vec3Array x = grid.positions();
  Topology before = buildTopology(x.size(), torusTriangles(grid), x);
  ASSERT_TRUE(before.isClosed());
  for (size_t k = 0; k < before.springCount(); ++k) before.restLength[k] = 100.0f + static_cast<float>(k);
  const std::vector<uint32_t> alive(x.size(), 1u);
  ensureColouring(alive, before);  // the solver's lists of the old mesh, which the new one must not keep
  ensurePatches(alive, 2, before);
  ASSERT_FALSE(before.patchOf.empty());
  // Edges four apart along both directions collapse, each to its lower end: no two share a triangle.
  std::vector<uint32_t> into(x.size());
  for (uint32_t i = 0; i < into.size(); ++i) into[i] = i;
  for (size_t r = 1; r < grid.rows; r += 4)
    for (size_t c = 1; c + 1 < grid.columns; c += 4) into[grid.at(r, c + 1)] = grid.at(r, c);
  std::vector<uint32_t> triangles;
  for (size_t t = 0; t < before.triangleCount(); ++t) {
    const uint32_t a = into[before.triangles[3 * t]], b = into[before.triangles[3 * t + 1]],
                   c = into[before.triangles[3 * t + 2]];
    if (a != b && b != c && a != c) triangles.insert(triangles.end(), {a, b, c});
  }
  constexpr float prestrain = 0.1f;
  std::vector<uint32_t> from, fromByRebuild;
  const Topology collapsed = collapsedTopology(before, triangles, into, x, prestrain, &from);
  const Topology rebuilt = rebuildTopology(before, triangles, x, prestrain, &fromByRebuild);
  EXPECT_EQ(collapsed.triangles, rebuilt.triangles);
  EXPECT_EQ(collapsed.springEnds, rebuilt.springEnds);
  EXPECT_EQ(collapsed.restLength, rebuilt.restLength);  // the same float operations: equal to the bit
  EXPECT_EQ(from, fromByRebuild);
  EXPECT_GT(std::count(from.begin(), from.end(), kMadeSpring), 0);
  for (size_t k = 0; k < from.size(); ++k) {  // a kept spring's rest length is the one it had
    if (from[k] == kMadeSpring) continue;
    EXPECT_EQ(collapsed.restLength[k], before.restLength[from[k]]) << "spring " << k;
  }
  EXPECT_EQ(collapsed.springOffset, rebuilt.springOffset);
  EXPECT_EQ(collapsed.springIndex, rebuilt.springIndex);
  EXPECT_EQ(collapsed.springNeighbour, rebuilt.springNeighbour);
  EXPECT_EQ(collapsed.triangleOffset, rebuilt.triangleOffset);
  EXPECT_EQ(collapsed.triangleCorner, rebuilt.triangleCorner);
  EXPECT_EQ(collapsed.boundary, rebuilt.boundary);
  EXPECT_EQ(collapsed.isClosed(), rebuilt.isClosed());
  EXPECT_TRUE(collapsed.isClosed());
  EXPECT_EQ(collapsed.contacts, rebuilt.contacts);
  for (const auto* lists : {&collapsed.colourOffset, &collapsed.colourOrder, &collapsed.patchOf, &collapsed.patchOffset,
                            &collapsed.patchMembers, &collapsed.patchRowOffset, &collapsed.patchRow})
    EXPECT_TRUE(lists->empty());
  EXPECT_EQ(collapsed.patchRings, 0);
}

}  // namespace
}  // namespace gb
