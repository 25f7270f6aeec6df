#pragma once
// Small hand-made films for unit tests.

#include <vector>

#include "film.h"

namespace gb::test {

// A film from explicit positions and counter-clockwise triangles, with its material initialised.
inline Film makeFilm(const Params& params, const std::vector<Vec3>& positions, std::vector<uint32_t> triangles) {
  Film film;
  film.state.resize(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) film.state.position.set(i, positions[i]);
  film.topology = buildTopology(positions.size(), std::move(triangles), film.state.position);
  initialiseFilmMaterial(params, film);
  return film;
}

// A regular hexagon of unit circumradius around particle 0 in the z = 0 plane: one interior particle with a
// six-particle one-ring, all triangles counter-clockwise seen from +z.
inline Film makeHexagon(const Params& params) {
  std::vector<Vec3> p = {Vec3::Zero()};
  std::vector<uint32_t> tri;
  for (int k = 0; k < 6; ++k) {
    const float a = static_cast<float>(k) * 3.14159265f / 3.0f;
    p.emplace_back(std::cos(a), std::sin(a), 0.0f);
    tri.insert(tri.end(), {0u, static_cast<uint32_t>(1 + k), static_cast<uint32_t>(1 + (k + 1) % 6)});
  }
  return makeFilm(params, p, tri);
}

}  // namespace gb::test
