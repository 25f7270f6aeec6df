#include "topology/pinch_off.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "stages/stages.h"

namespace gb {

std::vector<uint32_t> boundaryLoop(const Topology& topo) {
  // Directed boundary edges: an edge a->b of a triangle whose reverse b->a belongs to no triangle. Found per
  // particle from its own triangles (b leaves a, but no triangle of a enters a from b), not from a map of
  // every edge: film growth asks for the loop every frame, over ~60,000 edges.
  std::vector<std::pair<uint32_t, uint32_t>> next;  // boundary edges, sorted by their first particle
  std::vector<uint32_t> leaving, entering;
  for (uint32_t a = 0; a < topo.particleCount(); ++a) {
    if (!topo.boundary[a]) continue;  // both ends of an edge of one triangle are flagged (buildTopology)
    leaving.clear();
    entering.clear();
    for (uint32_t k = topo.triangleOffset[a]; k < topo.triangleOffset[a + 1]; ++k) {
      const uint32_t c = topo.triangleCorner[k] % 3;
      const uint32_t* corner = topo.triangleOf(topo.triangleCorner[k]);
      leaving.push_back(corner[(c + 1) % 3]);
      entering.push_back(corner[(c + 2) % 3]);
    }
    std::sort(leaving.begin(), leaving.end());
    leaving.erase(std::unique(leaving.begin(), leaving.end()), leaving.end());
    for (uint32_t b : leaving) {
      if (std::find(entering.begin(), entering.end(), b) != entering.end()) continue;
      if (!next.empty() && next.back().first == a)
        throw std::runtime_error("pinch-off: the film's boundary is not a single loop");
      next.emplace_back(a, b);
    }
  }
  if (next.empty()) return {};
  const auto successor = [&next](uint32_t a) -> std::optional<uint32_t> {
    const auto it = std::lower_bound(next.begin(), next.end(), std::make_pair(a, 0u));
    if (it == next.end() || it->first != a) return std::nullopt;
    return it->second;
  };
  std::vector<uint32_t> loop = {next.front().first};
  while (loop.size() <= next.size()) {
    const std::optional<uint32_t> following = successor(loop.back());
    if (!following) throw std::runtime_error("pinch-off: the film's boundary is open");
    if (*following == loop.front()) break;
    loop.push_back(*following);
  }
  if (loop.size() != next.size()) throw std::runtime_error("pinch-off: the film's boundary is not a single loop");
  return loop;
}

namespace {

double signedVolume(const Film& film, const Vec3& origin) {
  double v = 0;
  for (size_t t = 0; t < film.topology.triangleCount(); ++t) v += triangleVolume(film.topology, film.state, t, origin);
  return v;
}

// Mean distance between neighbours along the loop.
float loopSpacing(const State& s, const std::vector<uint32_t>& loop) {
  float spacing = 0.0f;
  for (size_t k = 0; k < loop.size(); ++k)
    spacing += (s.position.get(loop[(k + 1) % loop.size()]) - s.position.get(loop[k])).norm() /
               static_cast<float>(loop.size());
  return spacing;
}

// The seam of a collapsed loop (the wands brought together: the string's two sides hang side by side): the
// loop's two halves, from its two farthest-apart particles, zipped to each other with no new particle,
// always closing the shorter gap first. Returns the triangles (L - 2 of them), or nothing when the halves
// are not side by side (a zip diagonal longer than maxGap: an open loop needs a cap).
std::vector<uint32_t> zipCollapsedLoop(const State& s, const std::vector<uint32_t>& loop, float maxGap) {
  const size_t n = loop.size();
  auto at = [&](size_t k) { return s.position.get(loop[k % n]); };
  size_t top = 0, bottom = 0;
  float farthest = -1.0f;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      if (const float d = (at(i) - at(j)).norm(); d > farthest) {
        farthest = d;
        top = i;
        bottom = j;
      }
  // Chain a runs forward from top to bottom, chain b backward; both end at bottom.
  std::vector<size_t> a, b;
  for (size_t k = top; k != bottom; k = (k + 1) % n) a.push_back(k);
  a.push_back(bottom);
  for (size_t k = top; k != bottom; k = (k + n - 1) % n) b.push_back(k);
  b.push_back(bottom);
  if (a.size() < 2 || b.size() < 2) return {};
  std::vector<uint32_t> triangles = {loop[a[0]], loop[a[1]], loop[b[1]]};
  size_t i = 1, j = 1;  // a[i] and b[j] face each other across the seam
  while (i + 1 < a.size() || j + 1 < b.size()) {
    const float viaA = i + 1 < a.size() ? (at(a[i + 1]) - at(b[j])).norm() : std::numeric_limits<float>::infinity();
    const float viaB = j + 1 < b.size() ? (at(b[j + 1]) - at(a[i])).norm() : std::numeric_limits<float>::infinity();
    if (std::min(viaA, viaB) > maxGap) return {};
    if (viaA <= viaB) {
      if (a[i + 1] != b[j]) triangles.insert(triangles.end(), {loop[a[i]], loop[a[i + 1]], loop[b[j]]});
      ++i;
    } else {
      if (b[j + 1] != a[i]) triangles.insert(triangles.end(), {loop[a[i]], loop[b[j + 1]], loop[b[j]]});
      ++j;
    }
  }
  if (triangles.size() != 3 * (n - 2)) return {};  // not a simple zip: leave it to the cap
  return triangles;
}

// The cap of an open loop: rings of the loop shrunk towards its centroid, each with fewer points, zipped
// together ring by ring, and a last particle at the centroid. Its triangles touch the loop only along loop
// edges, so no cap edge can coincide with an edge of the film. New particles are numbered from `first`
// and their positions appended to `added`. The rings are at most as many as keep the cap's particles within
// `mostParticles` (about loop size x rings / 2): a loop much longer than its film is wide (a film dipped between
// closed wands: a long string around a sliver) would otherwise get a cap of a hundred thousand particles.
std::vector<uint32_t> ringCap(const State& s, const std::vector<uint32_t>& loop, size_t first, size_t mostParticles,
                              std::vector<Vec3>& added) {
  Vec3 centre = Vec3::Zero();
  for (uint32_t v : loop) centre += s.position.get(v) / static_cast<float>(loop.size());
  float radius = 0.0f;
  for (uint32_t v : loop) radius = std::max(radius, (s.position.get(v) - centre).norm());
  const float spacing = loopSpacing(s, loop);
  const long ringsAtLoopSpacing = std::lround(radius / std::max(spacing, 1e-6f));
  const long ringsWithinBudget = static_cast<long>(2 * mostParticles / loop.size());
  const int rings = static_cast<int>(std::max(1L, std::min(ringsAtLoopSpacing, ringsWithinBudget)));
  // Point at fraction t (0..1) around the loop, shrunk by `scale` towards the centre.
  auto around = [&](double t, float scale) {
    const double at = t * static_cast<double>(loop.size());
    const size_t k = static_cast<size_t>(at) % loop.size();
    const float w = static_cast<float>(at - std::floor(at));
    const Vec3 p = (1 - w) * s.position.get(loop[k]) + w * s.position.get(loop[(k + 1) % loop.size()]);
    return Vec3(centre + scale * (p - centre));
  };
  std::vector<uint32_t> capTriangles;
  std::vector<uint32_t> outer(loop.begin(), loop.end());
  for (int ring = 1; ring <= rings; ++ring) {
    const float scale = 1.0f - static_cast<float>(ring) / static_cast<float>(rings);
    const size_t count =
        ring == rings ? 1
                      : std::max<size_t>(3, static_cast<size_t>(std::lround(static_cast<double>(loop.size()) * scale)));
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
  return capTriangles;
}

// The seam (the loop's particles, whose Voronoi areas grew by the seam's triangles, and the cap's new ones) is
// wetted to the film's mean thickness: a seam thinner than the film around it is where the free bubble cracks
// first (Algorithm 3). The film's last strips grown at a drying wire and the long triangles of a zip left the seam
// at a twentieth of the film's thickness, and the bubble then burst within a quarter second in one live show of six
// (docs/model.md, "Pinch-off"). The liquid is not made from nothing: the wet wire lets go of the film with the
// solution it still holds, and where it runs short the rest of the film gives it, every particle the same fraction
// of what it holds (a seam is small beside its bubble: a fraction of a percent), at most half of its liquid: a cap
// as large as its film (a sliver dipped between closed wands) is then thinner than the film.
void wetTheSeam(const Params& params, const std::vector<uint32_t>& loop, size_t first, Film& film) {
  State& s = film.state;
  std::vector<char> inSeam(s.size(), 0);
  for (uint32_t i : loop) inSeam[i] = 1;
  for (size_t i = first; i < s.size(); ++i) {
    inSeam[i] = 1;
    s.liquid[i] = 0.0f;  // initialiseNewParticles gave the cap a new film's liquid; it is taken below
  }
  double restLiquid = 0, restArea = 0;
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i] && !inSeam[i]) {
      restLiquid += s.liquid[i];
      restArea += s.voronoiArea[i];
    }
  if (restArea <= 0 || restLiquid <= 0) return;
  const double filmThickness = restLiquid / restArea;
  auto shortfall = [&](size_t i) { return std::max(0.0, filmThickness * s.voronoiArea[i] - s.liquid[i]); };
  double wanted = 0;
  for (size_t i = 0; i < s.size(); ++i)
    if (inSeam[i]) wanted += shortfall(i);
  if (wanted <= 0) return;
  const double fromWire = std::min(wanted, static_cast<double>(film.wireLiquid));
  const double fromFilm = std::min(wanted - fromWire, 0.5 * restLiquid);
  film.wireLiquid = static_cast<float>(std::max(0.0, film.wireLiquid - fromWire));
  const double filled = (fromWire + fromFilm) / wanted;  // of each seam particle's shortfall
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s.alive[i]) continue;
    s.liquid[i] = static_cast<float>(inSeam[i] ? s.liquid[i] + filled * shortfall(i)
                                               : s.liquid[i] * (1.0 - fromFilm / restLiquid));
    // The physical model's mass is the liquid a particle was made with, and so its surfactant (surfactantLiquid):
    // the seam is new film, as a strip grown at the wire is, while the rest of the film gives up liquid alone, as
    // drainage moves it.
    if (params.tensionModel != 1 || inSeam[i]) s.mass[i] = particleMass(params, s.voronoiArea[i], s.liquid[i]);
    filmState(params, 0.0f, s, i);
  }
}

}  // namespace

void orientAgainstLoop(const std::vector<uint32_t>& loop, std::vector<uint32_t>& seam) {
  bool sameWay = false;
  for (size_t t = 0; t < seam.size(); t += 3)
    for (int k = 0; k < 3; ++k)
      if (seam[t + k] == loop[0] && seam[t + (k + 1) % 3] == loop[1]) sameWay = true;
  if (sameWay)
    for (size_t t = 0; t < seam.size(); t += 3) std::swap(seam[t + 1], seam[t + 2]);
}

bool pinchOff(const Params& params, Film& film) {
  State& s = film.state;
  Topology& topo = film.topology;
  const std::vector<uint32_t> loop = boundaryLoop(topo);
  if (loop.size() < 3) return false;

  // A collapsed loop is zipped shut; an open one (or a zip that would reuse an edge of the film) gets a cap.
  // Springs: the film's keep their rest lengths; the seam's rest prestrained at their current length.
  const size_t first = s.size();
  std::vector<Vec3> added;
  State grown = s;
  auto close = [&](std::vector<uint32_t> seam) {
    orientAgainstLoop(loop, seam);
    grown = s;  // new particles appended: indices of the film stay
    grown.append(added.size());
    for (size_t k = 0; k < added.size(); ++k) grown.position.set(first + k, added[k]);
    std::vector<uint32_t> triangles = topo.triangles;
    triangles.insert(triangles.end(), seam.begin(), seam.end());
    return rebuildTopology(topo, std::move(triangles), grown.position, params.springPrestrain);
  };
  // Side by side: no farther apart than the wand tips when they pinch, or four loop spacings.
  const float maxGap = std::max(4.0f * loopSpacing(s, loop), 1.5f * params.pinchDistance);
  std::optional<Topology> closed;
  if (std::vector<uint32_t> zip = zipCollapsedLoop(s, loop, maxGap); !zip.empty()) {
    try {
      closed = close(std::move(zip));
    } catch (const std::runtime_error&) {  // a zip diagonal is already an edge of the film: non-manifold
    }
  }
  if (!closed) closed = close(ringCap(s, loop, first, s.size(), added));  // a cap no larger than the film
  if (!closed->isClosed()) throw std::logic_error("pinch-off: the capped film still has a boundary");

  Film result = std::move(film);
  result.state = std::move(grown);
  result.topology = std::move(*closed);
  initialiseNewParticles(params, result, first);
  wetTheSeam(params, loop, first, result);
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
