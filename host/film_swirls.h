#pragma once
// Small-scale thickness variation of the film for the interference colouring: the swirls of a real soap film.
//
// A soap film is never uniform: marginal regeneration at its borders pulls thin patches up into it, and
// Marangoni flows driven by surfactant and temperature gradients stir its thickness into swirls and vortices
// that the film carries as it moves (Couder, Chomaz and Rabaud, "On the hydrodynamics of soap films",
// Physica D 37, 1989; Kellay and Goldburg, "Two-dimensional turbulence: a review of some recent
// experiments", Rep. Prog. Phys. 65, 2002; Seychelles, Amarouchene, Bessafi and Kellay, "Thermal convection
// and emergence of isolated vortices in soap bubbles", PRL 100, 144501, 2008). The simulation resolves the
// film at the centimetre scale of its particles and models thickness through liquid per particle (stretching
// and drainage); the swirls below that are drawn, not simulated: every particle carries a thickness factor
// exp(sigma g - sigma^2 / 2), whose exponent g is a domain-warped fractal noise of unit spread (scales of 25,
// 12 and 6 cm) evaluated at the particle's material coordinate (where it was when the film was made). The field
// therefore moves with the film, stretches with it, and its mean factor is 1 (the simulated thickness is the
// mean). The warp drifts slowly with the particle's age, so the swirls keep turning as on a real bubble.
// Pure C++; the renderer uploads the factors (GB_RENDER_VARIATION).

#include <cstdint>
#include <vector>

#include "model/state.h"

namespace gb {

class FilmSwirls {
 public:
  // `sigma`: standard deviation of the log-thickness variation (0: none; 0.45 halves or doubles the thickness
  // over about one swirl in six).
  explicit FilmSwirls(float sigma = 0.45f) : sigma_(sigma) {}

  // The factors for this frame, one per particle of `film` (1 for a dead one). A particle is (re)seeded with
  // its current position as material coordinate when it is new (an index not seen before) or its lifetime went
  // back (a new film was made in its place). A seeded particle's factor is computed at once, the others' in
  // turn, one particle in 8 per call: the swirls turn over seconds.
  const std::vector<float>& update(const State& film);

  // log of the factor before scaling by sigma: the swirl field at material point x and age t (s); mean 0,
  // standard deviation about 1.
  static float logVariation(const Vec3& material, float age);

  [[nodiscard]] float sigma() const { return sigma_; }

 private:
  float sigma_;
  std::vector<Vec3> material_;
  std::vector<float> lastLifetime_;
  std::vector<float> factor_;
  size_t phase_ = 0;  // which particles (i mod 8) this update refreshes
};

}  // namespace gb
