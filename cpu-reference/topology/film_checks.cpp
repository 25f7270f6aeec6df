#include "topology/film_checks.h"

#include <algorithm>
#include <cmath>

#include "topology/collision.h"
#include "topology/film_growth.h"

namespace gb {

namespace {

// The rest-length rules' spring counts, each test loosened by `margin`: lengths and thicknesses nudged towards
// the side on which the rule acts.
void countSprings(const Params& params, const Film& film, float margin, FilmChecks& checks) {
  const Topology& topo = film.topology;
  const State& s = film.state;
  const float dipThickness = initialThickness(params);
  const float more = 1.0f + margin, less = 1.0f - margin;
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    const float length = (s.position.get(a) - s.position.get(b)).norm(), rest = topo.restLength[k];
    const bool wireA = topo.boundary[a] != 0, wireB = topo.boundary[b] != 0;
    if (!s.alive[a] || !s.alive[b]) continue;
    if (wireA != wireB) {
      checks.rungs += 1.0f;
      checks.rungRest += rest;
      if (rungPaysOut(length * more, rest, params.growthStretch)) checks.rungsPastGrowth += 1.0f;
    }
    if (wireA && wireB) {
      checks.wireEdges += 1.0f;
      checks.wireEdgeLength += length;
    }
    const float thinner = std::min(s.thickness[a], s.thickness[b]), thicker = std::max(s.thickness[a], s.thickness[b]);
    if (!wireA && !wireB) {
      if (springYields(length * more, rest, thinner * more, params.yieldStretch, params.yieldThickness))
        checks.yielding += 1.0f;
      if (springContracts(length * less, rest, thicker * less, dipThickness)) checks.slack += 1.0f;
    }
    if (springCrowded(length * less, rest, thicker * more, dipThickness)) checks.crowded += 1.0f;
  }
}

}  // namespace

FilmChecks checkFilm(const Params& params, const Film& film, const FilmProbe& probe, float margin) {
  const State& s = film.state;
  FilmChecks checks;
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s.alive[i]) continue;
    ++checks.particles;
    const Vec3 x = s.position.get(i), v = s.velocity.get(i);
    if (!particleStable(x, v, margin)) checks.unstable = true;
    checks.lowest = std::min(checks.lowest, x.y());
    if (s.voronoiArea[i] > 0) checks.thinnest = std::min(checks.thinnest, s.thickness[i]);
  }
  for (int w = 0; w < 2; ++w) {
    checks.nearestTip[w] = nearestParticle(s, probe.tips[w]).distance;
    checks.winding[w] = static_cast<float>(windingNumber(film, probe.tips[w]));
  }
  checks.hardestImpact = hardestImpact(params, probe.frameTime, film).number;
  countSprings(params, film, margin, checks);
  const ContractionEnergy contraction = contractionEnergy(params, film);
  checks.contractionQuadratic = contraction.quadratic;
  checks.contractionLinear = contraction.linear;
  return checks;
}

}  // namespace gb
