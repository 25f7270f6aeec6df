#include "collision.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace gb {

namespace {

using Cell = std::array<int, 3>;

uint64_t cellKey(const Cell& c) {
  // 21 bits per axis: cells of a few centimetres cover +-20 km.
  auto bits = [](int v) { return static_cast<uint64_t>(v + (1 << 20)) & 0x1fffff; };
  return bits(c[0]) | (bits(c[1]) << 21) | (bits(c[2]) << 42);
}

Cell cellOf(const Vec3& x, float size) {
  return {static_cast<int>(std::floor(x.x() / size)), static_cast<int>(std::floor(x.y() / size)),
          static_cast<int>(std::floor(x.z() / size))};
}

bool isOneRingNeighbour(const Topology& topo, uint32_t i, uint32_t j) {
  const auto begin = topo.springNeighbour.begin() + topo.springOffset[i];
  const auto end = topo.springNeighbour.begin() + topo.springOffset[i + 1];
  return std::find(begin, end, j) != end;
}

// Living particles that are still part of the film (a particle whose triangles all tore is not).
bool inFilm(const Film& film, uint32_t i) {
  return film.state.alive[i] && film.topology.triangleOffset[i + 1] > film.topology.triangleOffset[i];
}

}  // namespace

size_t findContacts(const Params& p, float margin, Film& film) {
  const State& s = film.state;
  Topology& topo = film.topology;
  const size_t n = s.size();
  const float reach = p.collisionDistance + margin;
  std::vector<std::vector<uint32_t>> lists(n);
  if (reach > 0 && p.collisionStiffness > 0) {
    std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
    for (uint32_t i = 0; i < n; ++i)
      if (inFilm(film, i)) grid[cellKey(cellOf(s.position.get(i), reach))].push_back(i);
    constexpr float acrossCosine = 0.7071f;  // 45 degrees
    // Each particle fills its own list from the read-only grid: parallel, and the same lists in any order.
#pragma omp parallel for schedule(dynamic, 256)
    for (uint32_t i = 0; i < n; ++i) {
      if (!inFilm(film, i)) continue;
      const Vec3 xi = s.position.get(i), ni = s.normal.get(i);
      const Cell c = cellOf(xi, reach);
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            const auto found = grid.find(cellKey({c[0] + dx, c[1] + dy, c[2] + dz}));
            if (found == grid.end()) continue;
            for (uint32_t j : found->second) {
              if (j == i) continue;
              const Vec3 d = s.position.get(j) - xi;
              const float len = d.norm();
              if (!(len < reach) || len <= 0) continue;
              const bool across = std::abs(ni.dot(d)) > acrossCosine * len ||
                                  std::abs(s.normal.get(j).dot(d)) > acrossCosine * len;
              if (across && !isOneRingNeighbour(topo, i, j)) lists[i].push_back(j);
            }
          }
      std::sort(lists[i].begin(), lists[i].end());
    }
  }
  std::vector<uint32_t> packed(n + 1, 0u);
  size_t total = 0;
  for (size_t i = 0; i < n; ++i) {
    packed[i] = static_cast<uint32_t>(total);
    total += lists[i].size();
  }
  packed[n] = static_cast<uint32_t>(total);
  for (const auto& list : lists) packed.insert(packed.end(), list.begin(), list.end());
  topo.contacts = std::move(packed);
  return total / 2;
}

float impactNumber(const Params& params, float approachSpeed, float elasticity) {
  if (approachSpeed <= 0.0f || elasticity <= 0.0f) return 0.0f;
  return params.filmInertia * approachSpeed * approachSpeed / elasticity;
}

Impact hardestImpact(const Params& params, float frameTime, const Film& film) {
  const State& s = film.state;
  const std::vector<uint32_t>& contacts = film.topology.contacts;
  const size_t n = s.size();
  Impact hardest;
  if (contacts.size() <= n) return hardest;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t k = contacts[i]; k < contacts[i + 1]; ++k) {
      const uint32_t j = contacts[n + 1 + k];
      if (j < i || !s.alive[i] || !s.alive[j]) continue;  // each pair once
      const Vec3 d = s.position.get(j) - s.position.get(i);
      const float distance = d.norm();
      if (distance <= 0.0f) continue;
      const float approach = -(s.velocity.get(j) - s.velocity.get(i)).dot(d) / distance;
      if (!(distance - approach * frameTime < params.collisionDistance)) continue;  // no contact this frame
      const float number = impactNumber(params, approach, 0.5f * (s.elasticity[i] + s.elasticity[j]));
      if (number <= hardest.number) continue;
      hardest.number = number;
      hardest.particle = s.velocity.get(i).squaredNorm() >= s.velocity.get(j).squaredNorm() ? i : j;
    }
  return hardest;
}

Nearest nearestParticle(const State& s, const Vec3& x) {
  Nearest nearest{0, std::numeric_limits<float>::infinity()};
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s.alive[i]) continue;
    const float d = (s.position.get(i) - x).norm();
    if (d < nearest.distance) nearest = {i, d};
  }
  return nearest;
}

double windingNumber(const Film& film, const Vec3& x) {
  const Topology& topo = film.topology;
  double solidAngle = 0;
  for (size_t t = 0; t < topo.triangleCount(); ++t) {
    const Eigen::Vector3d a = (film.state.position.get(topo.triangles[3 * t]) - x).cast<double>();
    const Eigen::Vector3d b = (film.state.position.get(topo.triangles[3 * t + 1]) - x).cast<double>();
    const Eigen::Vector3d c = (film.state.position.get(topo.triangles[3 * t + 2]) - x).cast<double>();
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    solidAngle += 2.0 * std::atan2(numerator, denominator);
  }
  return solidAngle / (4.0 * 3.14159265358979323846);
}

}  // namespace gb
