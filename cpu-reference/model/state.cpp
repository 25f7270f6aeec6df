#include "model/state.h"

#include <algorithm>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <utility>

namespace gb {

namespace {

// A new particle's value of an array (its line of device_data.h), as the array's element type.
template <class Values>
typename Values::value_type createdValue(const Values&, const ParticleArrayInfo& info) {
  return static_cast<typename Values::value_type>(info.created);
}

}  // namespace

void State::resize(size_t n) {
  forEachParticleArray(*this, [n](auto& array, const ParticleArrayInfo& info) {
    forEachComponent(array, [&](auto& values, int) { values.assign(n, createdValue(values, info)); });
  });
}

void State::append(size_t count) {
  const size_t n = size() + count;
  forEachParticleArray(*this, [n](auto& array, const ParticleArrayInfo& info) {
    forEachComponent(array, [&](auto& values, int) { values.resize(n, createdValue(values, info)); });
  });
}

void State::removeFrom(size_t first) {
  forEachParticleArray(*this, [first](auto& array, const ParticleArrayInfo&) {
    forEachComponent(array, [&](auto& values, int) { values.resize(std::min(first, values.size())); });
  });
}

Vec3 centroid(const State& s) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  size_t count = 0;
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i]) {
      sum += s.position.get(i).cast<double>();
      ++count;
    }
  return count ? Vec3((sum / static_cast<double>(count)).cast<float>()) : Vec3::Zero();
}

namespace {

using Edge = std::pair<uint32_t, uint32_t>;
Edge undirected(uint32_t a, uint32_t b) { return a < b ? Edge{a, b} : Edge{b, a}; }

}  // namespace

std::vector<EdgeUse> edgeUses(size_t particleCount, const std::vector<uint32_t>& triangles) {
  const auto edge = [&](size_t t, int c) { return undirected(triangles[t + c], triangles[t + (c + 1) % 3]); };
  std::vector<uint32_t> start(particleCount + 1, 0);  // edges filed under their lower end
  for (size_t t = 0; t < triangles.size(); t += 3)
    for (int c = 0; c < 3; ++c) ++start[edge(t, c).first + 1];
  for (size_t i = 0; i < particleCount; ++i) start[i + 1] += start[i];
  std::vector<uint32_t> upper(start[particleCount]), fill(start.begin(), start.end() - 1);
  for (size_t t = 0; t < triangles.size(); t += 3)
    for (int c = 0; c < 3; ++c) {
      const auto [lo, hi] = edge(t, c);
      upper[fill[lo]++] = hi;
    }
  std::vector<EdgeUse> uses;
  for (uint32_t i = 0; i < particleCount; ++i) {
    const auto first = upper.begin() + start[i], last = upper.begin() + start[i + 1];
    std::sort(first, last);  // a particle's few edges
    for (auto run = first; run != last;) {
      const auto next = std::upper_bound(run, last, *run);
      uses.push_back({i, *run, static_cast<int>(next - run)});
      run = next;
    }
  }
  return uses;
}

namespace {

bool noEdgeOfOneTriangle(const std::vector<EdgeUse>& uses) {
  return !uses.empty() && std::none_of(uses.begin(), uses.end(), [](const EdgeUse& e) { return e.triangles == 1; });
}

// buildAdjacency but for Topology::closed, which needs every edge's uses: buildTopology has them already.
void buildAdjacencyArrays(Topology& topo) {
  const size_t n = topo.particleCount();
  topo.colourOffset.clear();  // the springs changed: the solver's colouring is made anew (colouring.h)
  topo.colourOrder.clear();
  topo.patchOffset.clear();  // and so are the coarse correction's patches (coarse_correction.h)
  // Spring CSR: counting sort by particle, springs in increasing id within each particle.
  topo.springOffset.assign(n + 1, 0);
  for (size_t s = 0; s < topo.springCount(); ++s) {
    ++topo.springOffset[topo.springEnds[2 * s] + 1];
    ++topo.springOffset[topo.springEnds[2 * s + 1] + 1];
  }
  for (size_t i = 0; i < n; ++i) topo.springOffset[i + 1] += topo.springOffset[i];
  topo.springIndex.assign(topo.springOffset[n], 0);
  topo.springNeighbour.assign(topo.springOffset[n], 0);
  std::vector<uint32_t> fill(topo.springOffset.begin(), topo.springOffset.end() - 1);
  for (uint32_t s = 0; s < topo.springCount(); ++s) {
    const uint32_t a = topo.springEnds[2 * s], b = topo.springEnds[2 * s + 1];
    topo.springIndex[fill[a]] = s;
    topo.springNeighbour[fill[a]++] = b;
    topo.springIndex[fill[b]] = s;
    topo.springNeighbour[fill[b]++] = a;
  }
  // Triangle CSR, same scheme.
  topo.triangleOffset.assign(n + 1, 0);
  for (uint32_t v : topo.triangles) ++topo.triangleOffset[v + 1];
  for (size_t i = 0; i < n; ++i) topo.triangleOffset[i + 1] += topo.triangleOffset[i];
  topo.triangleCorner.assign(topo.triangleOffset[n], 0);
  fill.assign(topo.triangleOffset.begin(), topo.triangleOffset.end() - 1);
  for (uint32_t corner = 0; corner < topo.triangles.size(); ++corner)
    topo.triangleCorner[fill[topo.triangles[corner]]++] = corner;
  topo.contacts.assign(n + 1, 0u);  // no contacts until the collision search runs
}

}  // namespace

void buildAdjacency(Topology& topo) {
  buildAdjacencyArrays(topo);
  topo.closed = noEdgeOfOneTriangle(edgeUses(topo.particleCount(), topo.triangles));
}

Topology buildTopology(size_t particleCount, std::vector<uint32_t> triangles, const Vec3Array& positions) {
  Topology topo;
  topo.triangles = std::move(triangles);
  topo.boundary.assign(particleCount, 0u);
  for (uint32_t v : topo.triangles)
    if (v >= particleCount) throw std::runtime_error("triangle refers to a particle that does not exist");
  const std::vector<EdgeUse> uses = edgeUses(particleCount, topo.triangles);
  for (const EdgeUse& e : uses) {
    if (e.triangles > 2) throw std::runtime_error("non-manifold mesh: an edge is shared by more than two triangles");
    if (e.triangles == 1) topo.boundary[e.lower] = topo.boundary[e.upper] = 1u;  // the film's edge: the wire
    topo.springEnds.push_back(e.lower);
    topo.springEnds.push_back(e.upper);
    topo.restLength.push_back((positions.get(e.lower) - positions.get(e.upper)).norm());
  }
  buildAdjacencyArrays(topo);
  topo.closed = noEdgeOfOneTriangle(uses);
  return topo;
}

Topology rebuildTopology(const Topology& previous, std::vector<uint32_t> triangles, const Vec3Array& positions,
                         float prestrain, std::vector<uint32_t>* from) {
  // An old spring is found in its lower end's old one-ring (a few entries): a sorted copy of every spring would cost
  // the merging of a free bubble's crowded particles a millisecond a frame.
  const auto oldSpring = [&](uint32_t a, uint32_t b) -> uint32_t {
    if (a >= previous.particleCount()) return kMadeSpring;  // appended since: all its springs are new
    for (uint32_t k = previous.springOffset[a]; k < previous.springOffset[a + 1]; ++k)
      if (previous.springNeighbour[k] == b) return previous.springIndex[k];
    return kMadeSpring;
  };
  Topology topo = buildTopology(positions.size(), std::move(triangles), positions);
  if (from) from->assign(topo.springCount(), kMadeSpring);
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const uint32_t old = oldSpring(topo.springEnds[2 * k], topo.springEnds[2 * k + 1]);
    topo.restLength[k] = old != kMadeSpring ? previous.restLength[old] : topo.restLength[k] * (1.0f - prestrain);
    if (from) (*from)[k] = old;
  }
  return topo;
}

Topology collapsedTopology(Topology previous, std::vector<uint32_t> triangles, const std::vector<uint32_t>& into,
                           const Vec3Array& positions, float prestrain, std::vector<uint32_t>* from) {
  const size_t springs = previous.springCount();
  const auto endsOf = [&](size_t k) { return Edge{previous.springEnds[2 * k], previous.springEnds[2 * k + 1]}; };
  bool ordered = true;
  for (size_t k = 0; k < springs && ordered; ++k)
    ordered = endsOf(k).first < endsOf(k).second && (k == 0 || endsOf(k - 1) < endsOf(k));
  if (!previous.isClosed() || !ordered)
    return rebuildTopology(previous, std::move(triangles), positions, prestrain, from);
  const auto had = [&](uint32_t a, uint32_t b) {
    for (uint32_t k = previous.springOffset[a]; k < previous.springOffset[a + 1]; ++k)
      if (previous.springNeighbour[k] == b) return true;
    return false;
  };
  const auto stays = [&](size_t k) {
    return into[endsOf(k).first] == endsOf(k).first && into[endsOf(k).second] == endsOf(k).second;
  };
  // The springs whose end moved, where they now lie: the collapsed edge itself vanishes, and one that ends where the
  // survivor already had a spring is that spring.
  std::vector<Edge> moved;
  for (size_t k = 0; k < springs; ++k) {
    if (stays(k)) continue;
    const uint32_t a = into[endsOf(k).first], b = into[endsOf(k).second];
    if (a != b && !had(a, b)) moved.push_back(undirected(a, b));
  }
  std::sort(moved.begin(), moved.end());
  moved.erase(std::unique(moved.begin(), moved.end()), moved.end());

  std::vector<uint32_t> springEnds;
  std::vector<float> restLength;
  springEnds.reserve(2 * (springs + moved.size()));
  restLength.reserve(springs + moved.size());
  if (from) from->clear();
  const auto add = [&](Edge e, float rest, uint32_t old) {
    springEnds.push_back(e.first);
    springEnds.push_back(e.second);
    restLength.push_back(rest);
    if (from) from->push_back(old);
  };
  const auto addMoved = [&](Edge e) {
    add(e, (positions.get(e.first) - positions.get(e.second)).norm() * (1.0f - prestrain), kMadeSpring);
  };
  auto next = moved.begin();
  for (size_t k = 0; k < springs; ++k) {  // both in (lower, upper) order: merged as they come
    if (!stays(k)) continue;
    for (; next != moved.end() && *next < endsOf(k); ++next) addMoved(*next);
    add(endsOf(k), previous.restLength[k], static_cast<uint32_t>(k));
  }
  for (; next != moved.end(); ++next) addMoved(*next);
  // The previous topology's arrays hold the new one: made anew in the memory they have (a fresh allocation for each
  // was a quarter of a round's time in page faults), and what a rebuild leaves empty emptied.
  Topology topo = std::move(previous);
  topo.triangles = std::move(triangles);
  topo.springEnds = std::move(springEnds);
  topo.restLength = std::move(restLength);
  std::fill(topo.boundary.begin(), topo.boundary.end(), 0u);  // closed before, and collapsing edges keeps it so
  for (std::vector<uint32_t>* patches : {&topo.patchOf, &topo.patchMembers, &topo.patchRowOffset, &topo.patchRow})
    patches->clear();
  topo.patchRings = 0;
  buildAdjacencyArrays(topo);
  topo.closed = true;
  return topo;
}

namespace {

// Grows a CSR array's rows to `rows` (new rows empty), then row i by extra[i] entries at its end, left for the caller
// to fill; each column (the arrays the offsets index) moves with its rows. Returns where each row's new entries start.
std::vector<uint32_t> growRows(std::vector<uint32_t>& offset, std::initializer_list<std::vector<uint32_t>*> columns,
                               const std::vector<uint32_t>& extra) {
  if (offset.empty()) offset.push_back(0);  // a mesh of no particles yet
  const size_t rows = extra.size();
  const uint32_t entries = offset.back();
  offset.resize(rows + 1, entries);
  std::vector<uint32_t> newOffset(rows + 1, 0);
  for (size_t i = 0; i < rows; ++i) newOffset[i + 1] = newOffset[i] + (offset[i + 1] - offset[i]) + extra[i];
  for (std::vector<uint32_t>* column : columns) {
    column->resize(newOffset[rows]);
    // From the last row to the first, each run of rows that moves by the same distance in one move: a row only moves
    // up, past where the rows before it lie.
    size_t end = rows;
    while (end > 0) {
      size_t begin = end - 1;
      const uint32_t shift = newOffset[begin] - offset[begin];
      while (begin > 0 && extra[begin - 1] == 0) --begin;  // a row's extra entries move the rows after it
      if (shift > 0)
        std::copy_backward(column->begin() + offset[begin], column->begin() + offset[end],
                           column->begin() + offset[end] + shift);
      end = begin;
    }
  }
  std::vector<uint32_t> next(rows);
  for (size_t i = 0; i < rows; ++i) next[i] = newOffset[i] + (offset[i + 1] - offset[i]);
  offset = std::move(newOffset);
  return next;
}

}  // namespace

void appendTriangles(Topology& topo, size_t particleCount, const std::vector<uint32_t>& added,
                     const Vec3Array& positions, float prestrain) {
  const size_t oldCount = topo.particleCount();
  if (particleCount < oldCount) throw std::logic_error("appendTriangles: a mesh only grows");
  if (added.size() % 3 != 0) throw std::runtime_error("appendTriangles: triangles come as three corners each");
  for (uint32_t v : added)
    if (v >= particleCount) throw std::runtime_error("triangle refers to a particle that does not exist");
  // The springs the mesh has, and how many of its triangles use each: found in their lower end's rows.
  const auto oldSpring = [&](uint32_t a, uint32_t b) -> std::optional<uint32_t> {
    if (b >= oldCount) return std::nullopt;
    for (uint32_t k = topo.springOffset[a]; k < topo.springOffset[a + 1]; ++k)
      if (topo.springNeighbour[k] == b) return topo.springIndex[k];
    return std::nullopt;
  };
  const auto trianglesOn = [&](uint32_t a, uint32_t b) {
    int uses = 0;
    for (uint32_t k = topo.triangleOffset[a]; k < topo.triangleOffset[a + 1]; ++k) {
      const uint32_t* tri = topo.triangleOf(topo.triangleCorner[k]);
      uses += tri[0] == b || tri[1] == b || tri[2] == b;
    }
    return uses;
  };
  // The added triangles' edges, each once, in (lower, upper) order, with their uses.
  std::vector<Edge> edges;
  edges.reserve(added.size());
  for (size_t t = 0; t < added.size(); t += 3)
    for (int c = 0; c < 3; ++c) edges.push_back(undirected(added[t + c], added[t + (c + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  std::vector<Edge> newSprings;
  for (auto run = edges.begin(); run != edges.end();) {
    const auto next = std::upper_bound(run, edges.end(), *run);
    const auto [a, b] = *run;
    const bool had = oldSpring(a, b).has_value();
    if ((next - run) + (had ? trianglesOn(a, b) : 0) > 2)
      throw std::runtime_error("non-manifold mesh: an edge is shared by more than two triangles");
    if (!had) newSprings.push_back({a, b});
    run = next;
  }

  // Nothing below throws: the mesh changes.
  const auto firstSpring = static_cast<uint32_t>(topo.springCount());
  const auto firstCorner = static_cast<uint32_t>(topo.triangles.size());
  topo.triangles.insert(topo.triangles.end(), added.begin(), added.end());
  for (const auto& [a, b] : newSprings) {
    topo.springEnds.push_back(a);
    topo.springEnds.push_back(b);
    topo.restLength.push_back((positions.get(a) - positions.get(b)).norm() * (1.0f - prestrain));
  }
  std::vector<uint32_t> extra(particleCount, 0);
  for (const auto& [a, b] : newSprings) ++extra[a], ++extra[b];
  std::vector<uint32_t> at = growRows(topo.springOffset, {&topo.springIndex, &topo.springNeighbour}, extra);
  for (uint32_t s = firstSpring; s < topo.springCount(); ++s) {
    const uint32_t a = topo.springEnds[2 * s], b = topo.springEnds[2 * s + 1];
    topo.springIndex[at[a]] = s;
    topo.springNeighbour[at[a]++] = b;
    topo.springIndex[at[b]] = s;
    topo.springNeighbour[at[b]++] = a;
  }
  std::fill(extra.begin(), extra.end(), 0u);
  for (uint32_t v : added) ++extra[v];
  at = growRows(topo.triangleOffset, {&topo.triangleCorner}, extra);
  for (auto corner = firstCorner; corner < topo.triangles.size(); ++corner)
    topo.triangleCorner[at[topo.triangles[corner]]++] = corner;

  // The touched particles' flags from their edges now; the others' edges did not change.
  topo.boundary.resize(particleCount, 0u);
  for (uint32_t p : added) {
    bool onEdge = false;
    for (uint32_t k = topo.springOffset[p]; k < topo.springOffset[p + 1] && !onEdge; ++k)
      onEdge = trianglesOn(p, topo.springNeighbour[k]) == 1;
    topo.boundary[p] = onEdge ? 1u : 0u;
  }
  topo.closed = topo.springCount() > 0 && !topo.hasBoundary();
  topo.colourOffset.clear();
  topo.colourOrder.clear();
  topo.patchOffset.clear();
  topo.contacts.assign(particleCount + 1, 0u);
}

}  // namespace gb
