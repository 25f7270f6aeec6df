#version 450
// filmState (cpu-reference/stages/stages.cpp): thickness e_i = liquid / A_Vor, elasticity Eq. (4) or the
// physical film tension (from the surfactant per area), age.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "film_tension.glsl"

// elasticity of cpu-reference/stages/stages.cpp: Marangoni while young, Gibbs after; Eq. (4) divided by k.
float elasticityOf(float thicknessValue, float age) {
  const float x = thicknessValue / params.elasticityThickness;
  if (age < params.marangoniLifetime) return params.elasticityWeight * 2.0 * x / (x + 2.0);
  const float g = max(x, params.gibbsFloorThickness / params.elasticityThickness);  // held below the floor
  return params.elasticityWeight * 4.0 * g / ((g + 2.0) * (g + 2.0));
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const float area = voronoiArea[i];
  thickness[i] = area > 0.0 ? liquid[i] / area : 0.0;
  elasticity[i] = params.tensionModel == 1 ? filmTension(area > 0.0 ? surfactantLiquid(i) / area : 0.0)
                                           : elasticityOf(thickness[i], lifetime[i]);
  lifetime[i] += steps[pc.stepIndex].dt;
}
