#version 450
// The frame's statistics, pass 1 (Simulation::stats of cpu-reference/simulation/simulation.cpp, reduced on the
// device): particle i's terms (GB_STAT_*) into half A of the statistics region. What the CPU sums per spring and per
// triangle, each particle sums over its one-ring: half of each of its springs' energy, a third of each of its
// triangles' area and cone volume, so that the film's sums are the same figures. The step's uniforms hold the frame's
// origin of the cone volumes in volumeOrigin.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "film_tension.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  float terms[GB_STATISTICS_TERMS];
  for (uint c = 0u; c < STATISTICS_TERMS; ++c) terms[c] = 0.0;
  if (alive[i] != 0u) {
    const vec3 x = LOAD3(position, i), v = LOAD3(velocity, i);
    const vec3 g = vec3(params.gravityX, params.gravityY, params.gravityZ);
    terms[GB_STAT_PARTICLES] = 1.0;
    terms[GB_STAT_KINETIC] = 0.5 * mass[i] * dot(v, v);
    terms[GB_STAT_POTENTIAL] = -(params.liquidDensity * liquid[i]) * dot(g, x);
    terms[GB_STAT_LIQUID] = liquid[i];
    terms[GB_STAT_THICKNESS] = thickness[i];
    terms[GB_STAT_AIR_FLOW] = length(LOAD3(airFlow, i));
    terms[GB_STAT_SPEED] = length(v);
    if (params.tensionModel == 1) {
      terms[GB_STAT_ELASTIC] = filmTensionEnergy(surfactantLiquid(i), voronoiArea[i]);
    } else {
      for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
        const uint j = springNeighbour[k];
        const float stretch = length(LOAD3(position, j) - x) - restLength[springIndex[k]];
        terms[GB_STAT_ELASTIC] += 0.5 * springEnergyOf(0.5 * (elasticity[i] + elasticity[j]), stretch);
      }
    }
    const vec3 origin = steps[pc.stepIndex].volumeOrigin.xyz;
    for (uint k = triangleOffset[i]; k < triangleOffset[i + 1u]; ++k) {
      const uint t = triangleCorner[k] / 3u;
      const vec3 a = LOAD3(position, triangles[3u * t]) - origin;
      const vec3 b = LOAD3(position, triangles[3u * t + 1u]) - origin;
      const vec3 c = LOAD3(position, triangles[3u * t + 2u]) - origin;
      terms[GB_STAT_AREA] += 0.5 * length(cross(b - a, c - a)) / 3.0;
      terms[GB_STAT_VOLUME] += dot(a, cross(b, c)) / 6.0 / 3.0;
    }
  }
  for (uint c = 0u; c < STATISTICS_TERMS; ++c) STATISTICS_A(c, i) = terms[c];
}
