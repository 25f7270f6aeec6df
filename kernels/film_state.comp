#version 450
// filmState (cpu-reference/stages/stages.cpp): thickness e_i = liquid / A_Vor, elasticity Eq. (4) or the
// physical film tension (from the surfactant per area), age.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

// elasticity of cpu-reference/stages/stages.cpp: Marangoni while young, Gibbs after; Eq. (4) divided by k.
float elasticityOf(float thicknessValue, float age) {
  const float x = thicknessValue / params.elasticityThickness;
  if (age < params.marangoniLifetime) return params.elasticityWeight * 2.0 * x / (x + 2.0);
  const float g = max(x, params.gibbsFloorThickness / params.elasticityThickness);  // held below the floor
  return params.elasticityWeight * 4.0 * g / ((g + 2.0) * (g + 2.0));
}

// filmTension of cpu-reference/stages/stages.cpp: 2 gamma, gamma from the thickness through Gibbs-Marangoni elasticity.
float filmTension(float thicknessValue) {
  const float gamma0 = params.surfaceTension;
  const float e0 = initialThicknessOf(params.areaWeight);
  const float gamma = gamma0 + 0.5 * params.gibbsElasticity * log(e0 / max(thicknessValue, 1e-12));
  return 2.0 * clamp(gamma, kLowestGammaFactor * gamma0, kHighestGammaFactor * gamma0);
}

// surfactantLiquid of cpu-reference/model/film.h: the liquid the particle was made with, which its mass still weighs.
float surfactantLiquid(uint i) { return mass[i] / params.liquidDensity; }

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const float area = voronoiArea[i];
  thickness[i] = area > 0.0 ? liquid[i] / area : 0.0;
  elasticity[i] = params.tensionModel == 1 ? filmTension(area > 0.0 ? surfactantLiquid(i) / area : 0.0)
                                           : elasticityOf(thickness[i], lifetime[i]);
  lifetime[i] += steps[pc.stepIndex].dt;
}
