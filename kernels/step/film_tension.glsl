// The physical tension model's film tension and its energy (tensionModel 1), for film_state and the frame's
// statistics. Each function has the name and the float operations of its C++ twin in cpu-reference/stages/stages.cpp
// (filmTensionEnergy's twin adds in double: the statistics' tests allow for the difference).

// filmTension: 2 gamma, gamma from the thickness through Gibbs-Marangoni elasticity.
float filmTension(float thicknessValue) {
  const float gamma0 = params.surfaceTension;
  const float e0 = initialThicknessOf(params.areaWeight);
  const float gamma = gamma0 + 0.5 * params.gibbsElasticity * log(e0 / max(thicknessValue, 1e-12));
  return 2.0 * clamp(gamma, kLowestGammaFactor * gamma0, kHighestGammaFactor * gamma0);
}

// filmTensionEnergy: the energy of `liquidValue` spread over `area`, the integral of the tension over the area.
float filmTensionEnergy(float liquidValue, float area) {
  const float e0 = initialThicknessOf(params.areaWeight), gamma0 = params.surfaceTension;
  const float gibbs = params.gibbsElasticity;
  const float tension = filmTension(area > 0.0 ? liquidValue / area : 0.0);
  if (!(gibbs > 0.0)) return tension * area;
  const float lower = liquidValue / e0 * exp(2.0 * (kLowestGammaFactor - 1.0) * gamma0 / gibbs);
  const float upper = liquidValue / e0 * exp(2.0 * (kHighestGammaFactor - 1.0) * gamma0 / gibbs);
  return tension * area - gibbs * (clamp(area, lower, upper) - lower);
}

// surfactantLiquid of cpu-reference/model/film.h: the liquid the particle was made with, which its mass still weighs.
float surfactantLiquid(uint i) { return mass[i] / params.liquidDensity; }
