#include "host/film_swirls.h"

#include <cmath>
#include <limits>

#include "host/procedural_noise.h"

namespace gb {

namespace {

// The fractal sum of fractal3 over 3 octaves of gain 0.5 has a standard deviation of about 0.27 (measured over
// 10^5 points, FilmSwirls.LogVariationHasUnitSpreadAndZeroMean); g is divided by it.
constexpr float kFractalSpread = 0.27f;
constexpr float kLargestScale = 0.25f;  // m, the largest swirls; the octaves add 1/2 and 1/4 of it (and finer
                                        // detail interpolated between particles)
constexpr float kWarp = 0.6f;           // how far (in largest scales) the warp displaces the lookup: swirling
constexpr float kTurnRate = 0.15f;      // 1/s: the warp field drifts one lattice cell in about 7 s
// Refreshing every factor each frame cost 6.7 ms at 25,650 particles, more than a real GPU takes to draw the
// frame. The warp turns so slowly that a factor 8 frames old is off by a few thousandths of a lattice cell: each
// update refreshes one particle in kRefreshEvery, in turn, and every particle (re)seeded in it.
constexpr size_t kRefreshEvery = 8;

}  // namespace

float FilmSwirls::logVariation(const Vec3& material, float age) {
  const Vec3 p = material / kLargestScale;
  const Vec3 drift(0.0f, 0.0f, kTurnRate * age);
  const Vec3 warp(noise::fractal3(0.7f * p + drift, 2, 21u),
                  noise::fractal3(0.7f * p + drift + Vec3(5.2f, 1.3f, 0), 2, 22u),
                  noise::fractal3(0.7f * p + drift + Vec3(1.7f, 9.2f, 0), 2, 23u));
  return noise::fractal3(p + kWarp * warp / kFractalSpread, 3, 31u) / kFractalSpread;
}

const std::vector<float>& FilmSwirls::update(const State& s) {
  const size_t n = s.size();
  if (material_.size() < n) {
    material_.resize(n, Vec3::Zero());
    lastLifetime_.resize(n, std::numeric_limits<float>::infinity());  // unseen: seeded below
  }
  factor_.resize(n, 1.0f);
  phase_ = (phase_ + 1) % kRefreshEvery;
  const float meanCorrection = 0.5f * sigma_ * sigma_;  // E[exp(sigma g)] = exp(sigma^2 / 2) for unit normal g
  for (size_t i = 0; i < n; ++i) {
    const bool seeded = s.lifetime[i] < lastLifetime_[i];
    if (seeded) material_[i] = s.position.get(i);
    lastLifetime_[i] = s.lifetime[i];
    if (!s.alive[i] || sigma_ <= 0.0f)
      factor_[i] = 1.0f;
    else if (seeded || i % kRefreshEvery == phase_)
      factor_[i] = std::exp(sigma_ * logVariation(material_[i], s.lifetime[i]) - meanCorrection);
  }
  return factor_;
}

}  // namespace gb
