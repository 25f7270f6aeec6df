#pragma once
// Small hand-made films for unit tests.

#include <cmath>
#include <random>
#include <vector>

#include "capture/scripted_gestures.h"
#include "model/film.h"
#include "stages/cpu_stepper.h"

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

// Two free parallel discs (ring films with their rims let go), the second `gap` metres further along +z,
// the first moving towards it at `speed`: a film about to collide with itself.
inline Film makeTwoSheets(const Params& params, float gap, float speed) {
  WandTool ring;
  ring.kind = ToolKind::Ring;
  const Film a = generateFilm(params, ring, gestureAt(Gesture::Straight, GestureOptions{}, 0.0));
  const size_t n = a.state.size();
  std::vector<Vec3> positions;
  for (size_t i = 0; i < n; ++i) positions.push_back(a.state.position.get(i));
  for (size_t i = 0; i < n; ++i) positions.push_back(a.state.position.get(i) + Vec3(0, 0, gap));
  std::vector<uint32_t> triangles = a.topology.triangles;
  for (uint32_t v : a.topology.triangles) triangles.push_back(static_cast<uint32_t>(v + n));
  Film film = makeFilm(params, positions, triangles);
  film.tool = ring;
  film.topology.boundary.assign(2 * n, 0u);  // nothing holds the rims
  for (size_t i = 0; i < n; ++i) film.state.velocity.set(i, Vec3(0, 0, speed));
  return film;
}

// A ring's film with its rim let go: a free disc in the wands' plane.
inline Film makeFreeDisc(const Params& params) {
  WandTool ring;
  ring.kind = ToolKind::Ring;
  Film film = generateFilm(params, ring, gestureAt(Gesture::Straight, GestureOptions{}, 0.0));
  film.topology.boundary.assign(film.state.size(), 0u);
  return film;
}

// Moves every particle by up to `fraction` of the film's first spring in every direction (random, from `seed`), keeps
// where it was as the step's start (previousPosition), and makes every seventh one a wire particle (which the
// energy budget places at its end position): a film on which every case of the one-ring formulas occurs.
inline void jitterWithWireParticles(Film& film, float fraction, unsigned seed) {
  State& s = film.state;
  const float spacing = film.topology.restLength[0];
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> jitter(-fraction * spacing, fraction * spacing);
  for (size_t i = 0; i < s.size(); ++i) {
    s.previousPosition.set(i, s.position.get(i));
    s.position.set(i, s.position.get(i) + Vec3(jitter(random), jitter(random), jitter(random)));
    film.topology.boundary[i] = i % 7 == 0 ? 1u : 0u;
  }
}

// Gives every particle the velocity of a rigid spin at `rate` (rad/s) about `axis` through the film's centroid.
inline void spin(Film& film, const Vec3& axis, float rate) {
  State& s = film.state;
  Vec3 centre = Vec3::Zero();
  for (size_t i = 0; i < s.size(); ++i) centre += s.position.get(i) / static_cast<float>(s.size());
  for (size_t i = 0; i < s.size(); ++i) s.velocity.set(i, rate * axis.normalized().cross(s.position.get(i) - centre));
}

// The default film folded along x = 0: the half at x > 0 turned about the y axis by `angle` (radians) onto the
// other half, the two halves `angle`'s complement apart (1.7 cm at 10 cm from the crease for 170 degrees), and
// moving at random up to 1 m/s.
inline Film foldedFilm(const Params& p, float angle, unsigned seed) {
  Film film = generateFilm(p, WandTool{}, gestureAt(Gesture::Straight, GestureOptions{}, 0.0));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (size_t i = 0; i < film.state.size(); ++i) {
    const Vec3 x = film.state.position.get(i);
    if (x.x() > 0) film.state.position.set(i, Vec3(x.x() * std::cos(angle), x.y(), x.z() + x.x() * std::sin(angle)));
    film.state.velocity.set(i, Vec3(u(rng), u(rng), u(rng)) / std::sqrt(3.0f));
  }
  CpuStepper::refreshGeometry(p, film);
  return film;
}

// Two sheets `gap` apart, the second shifted by `shift` along x, the whole turned by `angle` (radians) about
// (1, 2, 3): a pair across them lies sqrt(gap^2 + shift^2) apart.
inline Film shiftedSheets(const Params& p, float gap, float shift, float angle) {
  Film film = test::makeTwoSheets(p, gap, 0.0f);
  const size_t n = film.state.size();
  const Eigen::AngleAxisf turn(angle, Vec3(1, 2, 3).normalized());
  for (size_t i = 0; i < n; ++i) {
    const Vec3 x = film.state.position.get(i) + (i < n / 2 ? Vec3::Zero() : Vec3(shift, 0, 0));
    film.state.position.set(i, turn * x);
  }
  CpuStepper::refreshGeometry(p, film);
  return film;
}

}  // namespace gb::test
