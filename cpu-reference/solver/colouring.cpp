#include "solver/colouring.h"

#include <algorithm>

namespace gb {

namespace {

// Calls visit(j) for every particle coupled to i in the solver's sweep: its spring neighbours.
template <class Visit>
void forEachCoupled(const Topology& topo, size_t i, Visit&& visit) {
  for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) visit(topo.springNeighbour[k]);
}

}  // namespace

bool isSolverParticle(const std::vector<uint32_t>& alive, const Topology& topo, size_t i) {
  return alive[i] != 0 && topo.boundary[i] == 0;
}

void colourParticles(const std::vector<uint32_t>& alive, Topology& topo) {
  const size_t n = topo.particleCount();
  constexpr uint32_t kNone = ~0u;
  std::vector<uint32_t> colour(n, kNone);
  std::vector<uint32_t> usedBy;  // usedBy[c] == i: colour c is taken by a neighbour of i
  uint32_t colours = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!isSolverParticle(alive, topo, i)) continue;
    forEachCoupled(topo, i, [&](uint32_t j) {
      if (colour[j] != kNone) usedBy[colour[j]] = static_cast<uint32_t>(i);
    });
    uint32_t c = 0;
    while (c < colours && usedBy[c] == i) ++c;
    if (c == colours) {
      ++colours;
      usedBy.push_back(kNone);
    }
    colour[i] = c;
  }
  // Counting sort by colour keeps increasing particle order within a colour.
  topo.colourOffset.assign(colours + 1, 0u);
  for (size_t i = 0; i < n; ++i)
    if (colour[i] != kNone) ++topo.colourOffset[colour[i] + 1];
  for (uint32_t c = 0; c < colours; ++c) topo.colourOffset[c + 1] += topo.colourOffset[c];
  topo.colourOrder.assign(topo.colourOffset.back(), 0u);
  std::vector<uint32_t> next(topo.colourOffset.begin(), topo.colourOffset.end() - 1);
  for (size_t i = 0; i < n; ++i)
    if (colour[i] != kNone) topo.colourOrder[next[colour[i]]++] = static_cast<uint32_t>(i);
}

void ensureColouring(const std::vector<uint32_t>& alive, Topology& topo) {
  if (topo.colourOffset.empty()) colourParticles(alive, topo);
}

bool isValidColouring(const std::vector<uint32_t>& alive, const Topology& topo) {
  const size_t n = topo.particleCount();
  constexpr uint32_t kNone = ~0u;
  std::vector<uint32_t> colour(n, kNone);
  if (topo.colourOffset.empty()) return false;
  for (size_t c = 0; c + 1 < topo.colourOffset.size(); ++c)
    for (uint32_t k = topo.colourOffset[c]; k < topo.colourOffset[c + 1]; ++k) {
      const uint32_t i = topo.colourOrder[k];
      if (i >= n || colour[i] != kNone) return false;  // out of range or coloured twice
      colour[i] = static_cast<uint32_t>(c);
    }
  for (size_t i = 0; i < n; ++i) {
    if (isSolverParticle(alive, topo, i) != (colour[i] != kNone)) return false;
    bool clash = false;
    if (colour[i] != kNone) forEachCoupled(topo, i, [&](uint32_t j) { clash = clash || colour[j] == colour[i]; });
    if (clash) return false;
  }
  return true;
}

}  // namespace gb
