#include "pinch_off.h"

#include <cmath>
#include <map>
#include <stdexcept>

#include "stages.h"

namespace gb {

std::vector<uint32_t> boundaryLoop(const Topology& topo) {
  // Directed boundary edges: an edge a->b of a triangle whose reverse b->a belongs to no triangle.
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < topo.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) ++directed[{topo.triangles[3 * t + c], topo.triangles[3 * t + (c + 1) % 3]}];
  std::map<uint32_t, uint32_t> next;
  for (const auto& [edge, count] : directed)
    if (!directed.count({edge.second, edge.first})) {
      if (next.count(edge.first)) throw std::runtime_error("pinch-off: the film's boundary is not a single loop");
      next[edge.first] = edge.second;
    }
  if (next.empty()) return {};
  std::vector<uint32_t> loop = {next.begin()->first};
  while (loop.size() <= next.size()) {
    const auto it = next.find(loop.back());
    if (it == next.end()) throw std::runtime_error("pinch-off: the film's boundary is open");
    if (it->second == loop.front()) break;
    loop.push_back(it->second);
  }
  if (loop.size() != next.size()) throw std::runtime_error("pinch-off: the film's boundary is not a single loop");
  return loop;
}

namespace {

double signedVolume(const Film& film, const Vec3& origin) {
  double v = 0;
  for (size_t t = 0; t < film.topology.triangleCount(); ++t) v += triangleSignedVolume(film.topology, film.state, t, origin);
  return v;
}

}  // namespace

bool pinchOff(const Params& params, Film& film) {
  State& s = film.state;
  Topology& topo = film.topology;
  const std::vector<uint32_t> loop = boundaryLoop(topo);
  if (loop.size() < 3) return false;

  // The cap: rings of the loop shrunk towards its centroid, each with fewer points, zipped together
  // ring by ring, and a last particle at the centroid. Its triangles touch the loop only along loop edges,
  // so no cap edge can coincide with an edge of the film.
  Vec3 centre = Vec3::Zero();
  for (uint32_t v : loop) centre += s.position.get(v) / static_cast<float>(loop.size());
  float radius = 0.0f, spacing = 0.0f;
  for (uint32_t v : loop) radius = std::max(radius, (s.position.get(v) - centre).norm());
  for (size_t k = 0; k < loop.size(); ++k)
    spacing += (s.position.get(loop[(k + 1) % loop.size()]) - s.position.get(loop[k])).norm() / static_cast<float>(loop.size());
  const int rings = std::max(1, static_cast<int>(std::lround(radius / std::max(spacing, 1e-6f))));
  // Point at fraction t (0..1) around the loop, shrunk by `scale` towards the centre.
  auto around = [&](double t, float scale) {
    const double at = t * static_cast<double>(loop.size());
    const size_t k = static_cast<size_t>(at) % loop.size();
    const float w = static_cast<float>(at - std::floor(at));
    const Vec3 p = (1 - w) * s.position.get(loop[k]) + w * s.position.get(loop[(k + 1) % loop.size()]);
    return Vec3(centre + scale * (p - centre));
  };
  const size_t first = s.size();
  std::vector<Vec3> added;
  std::vector<uint32_t> capTriangles;
  std::vector<uint32_t> outer(loop.begin(), loop.end());
  for (int ring = 1; ring <= rings; ++ring) {
    const float scale = 1.0f - static_cast<float>(ring) / static_cast<float>(rings);
    const size_t count = ring == rings ? 1 : std::max<size_t>(3, static_cast<size_t>(std::lround(static_cast<double>(loop.size()) * scale)));
    std::vector<uint32_t> inner;
    for (size_t k = 0; k < count; ++k) {
      inner.push_back(static_cast<uint32_t>(first + added.size()));
      added.push_back(ring == rings ? centre : around(static_cast<double>(k) / static_cast<double>(count), scale));
    }
    // Zip: advance along whichever ring's next point comes first around the loop.
    const size_t no = outer.size(), ni = inner.size();
    size_t i = 0, j = 0;
    while (i < no || (ni > 1 && j < ni)) {
      const double nextOuter = static_cast<double>(i + 1) / static_cast<double>(no);
      const double nextInner = ni > 1 ? static_cast<double>(j + 1) / static_cast<double>(ni) : 2.0;
      if (i < no && (j >= ni || nextOuter <= nextInner)) {
        capTriangles.insert(capTriangles.end(), {outer[i], outer[(i + 1) % no], inner[j % ni]});
        ++i;
      } else {
        capTriangles.insert(capTriangles.end(), {outer[i % no], inner[(j + 1) % ni], inner[j]});
        ++j;
      }
    }
    outer = std::move(inner);
  }
  bool sameWay = false;  // does some cap triangle run loop[0] -> loop[1] like the film does?
  for (size_t t = 0; t < capTriangles.size(); t += 3)
    for (int k = 0; k < 3; ++k)
      if (capTriangles[t + k] == loop[0] && capTriangles[t + (k + 1) % 3] == loop[1]) sameWay = true;
  if (sameWay)
    for (size_t t = 0; t < capTriangles.size(); t += 3) std::swap(capTriangles[t + 1], capTriangles[t + 2]);

  // New particles appended: indices of the film stay.
  State grown = s;
  grown.append(added.size());
  for (size_t k = 0; k < added.size(); ++k) grown.position.set(first + k, added[k]);

  // Springs: the film's keep their rest lengths; the cap's rest prestrained at their current length.
  std::vector<uint32_t> triangles = topo.triangles;
  triangles.insert(triangles.end(), capTriangles.begin(), capTriangles.end());
  Topology closed = rebuildTopology(topo, std::move(triangles), grown.position, params.springPrestrain);
  if (!closed.isClosed()) throw std::logic_error("pinch-off: the capped film still has a boundary");

  Film result = std::move(film);
  result.state = std::move(grown);
  result.topology = std::move(closed);
  initialiseNewParticles(params, result, first);
  // Outward normals: a closed film encloses a positive volume.
  result.volumeOrigin = centroid(result.state);
  double volume = signedVolume(result, result.volumeOrigin);
  if (volume < 0) {
    for (size_t t = 0; t < result.topology.triangleCount(); ++t)
      std::swap(result.topology.triangles[3 * t + 1], result.topology.triangles[3 * t + 2]);
    buildAdjacency(result.topology);
    volume = -volume;
  }
  computeGeometry(result.topology, result.state);
  result.referenceVolume = static_cast<float>(volume);
  film = std::move(result);
  return true;
}

}  // namespace gb
