#version 450
// The frame's statistics and the film checks, pass 1 (Simulation::stats and checkFilm of
// cpu-reference/topology/film_checks.cpp, reduced on the device): particle i's terms (GB_STAT_*) into half A of the
// statistics region. What the CPU sums per spring and per triangle, each particle sums over its one-ring: half of
// each of its springs' energy and counts, a third of each of its triangles' area, cone volume and solid angles, so
// that the film's sums are the same figures. The step's uniforms hold the frame's origin of the cone volumes in
// volumeOrigin, the wand tips in leftPosition and rightPosition, and the frame's length in frameTime. The checks'
// thresholds are loosened by kFilmCheckMargin towards the side on which each rule acts.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "film_tension.glsl"

const float kNone = -3.4e38;  // a largest-kept term of a particle that has none
const float kMore = 1.0 + kFilmCheckMargin, kLess = 1.0 - kFilmCheckMargin;

// The solid angle of triangle (a, b, c) seen from the origin over 4 pi (windingNumber of collision.cpp, in float);
// 0 for a triangle with a corner at the origin (atan of 0 over 0 is undefined in GLSL).
float windingOf(vec3 a, vec3 b, vec3 c) {
  const float la = length(a), lb = length(b), lc = length(c);
  if (la * lb * lc == 0.0) return 0.0;
  const float numerator = dot(a, cross(b, c));
  const float denominator = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
  return 2.0 * atan(numerator, denominator) / (4.0 * 3.14159265);
}

// Particle i's half of its springs' energy and of the rest-length rules' counts (countSprings of film_checks.cpp).
void springTerms(uint i, vec3 x, inout float terms[GB_STATISTICS_TERMS]) {
  const float dipThickness = initialThicknessOf(params.areaWeight);
  const bool wireI = boundary[i] != 0u;
  for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
    const uint j = springNeighbour[k];
    const float len = length(LOAD3(position, j) - x), rest = restLength[springIndex[k]];
    const bool wireJ = boundary[j] != 0u;
    if (params.tensionModel != 1)
      terms[GB_STAT_ELASTIC] += 0.5 * springEnergyOf(0.5 * (elasticity[i] + elasticity[j]), len - rest);
    if (alive[j] == 0u) continue;
    if (wireI != wireJ) {
      terms[GB_STAT_RUNG_COUNT] += 0.5;
      terms[GB_STAT_RUNG_REST] += 0.5 * rest;
      if (rungPaysOut(len * kMore, rest, params.growthStretch)) terms[GB_STAT_RUNGS_PAST_GROWTH] += 0.5;
    }
    if (wireI && wireJ) {
      terms[GB_STAT_WIRE_EDGE_COUNT] += 0.5;
      terms[GB_STAT_WIRE_EDGES] += 0.5 * len;
    }
    const float thinner = min(thickness[i], thickness[j]), thicker = max(thickness[i], thickness[j]);
    if (!wireI && !wireJ) {
      if (springYields(len * kMore, rest, thinner * kMore, params.yieldStretch, params.yieldThickness))
        terms[GB_STAT_YIELDING] += 0.5;
      if (springContracts(len * kLess, rest, thicker * kLess, dipThickness)) terms[GB_STAT_SLACK] += 0.5;
      if (params.tensionModel == 0 && springContracts(len, rest, thicker, dipThickness)) {
        const float stiffness = 0.5 * (elasticity[i] + elasticity[j]);
        const float taut = tautRestLengthOf(len, rest, params.springPrestrain, params.energyNeutralContraction);
        terms[GB_STAT_CONTRACTION_QUADRATIC] += 0.5 * contractionQuadraticOf(stiffness, rest, taut);
        terms[GB_STAT_CONTRACTION_LINEAR] += 0.5 * contractionLinearOf(stiffness, len, rest, taut);
      }
    }
    if (springCrowded(len * kLess, rest, thicker * kMore, dipThickness)) terms[GB_STAT_CROWDED] += 0.5;
  }
}

// The hardest impact among particle i's contacts closing to within the collision distance in the frame
// (hardestImpact of collision.cpp).
float hardestImpactOf(uint i, vec3 x, vec3 v) {
  float hardest = 0.0;
  const uint base = pc.particles + 1u;
  for (uint k = contacts[i]; k < contacts[i + 1u]; ++k) {
    const uint j = contacts[base + k];
    if (alive[j] == 0u) continue;
    const vec3 d = LOAD3(position, j) - x;
    const float distance = length(d);
    if (distance <= 0.0) continue;
    const float approach = -dot(LOAD3(velocity, j) - v, d) / distance;
    if (!(distance - approach * steps[pc.stepIndex].frameTime < params.collisionDistance * kMore)) continue;
    hardest = max(hardest, impactNumberOf(params.filmInertia, approach, 0.5 * (elasticity[i] + elasticity[j])));
  }
  return hardest;
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  float terms[GB_STATISTICS_TERMS];
  for (uint c = 0u; c < STATISTICS_TERMS; ++c) terms[c] = GB_STAT_KEEPS_LARGEST(c) ? kNone : 0.0;
  terms[GB_STAT_UNSTABLE] = 0.0;
  terms[GB_STAT_IMPACT] = 0.0;
  const vec3 leftTip = steps[pc.stepIndex].leftPosition.xyz, rightTip = steps[pc.stepIndex].rightPosition.xyz;
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
    if (params.tensionModel == 1) terms[GB_STAT_ELASTIC] = filmTensionEnergy(surfactantLiquid(i), voronoiArea[i]);
    springTerms(i, x, terms);
    const bool finite = !any(isnan(x)) && !any(isinf(x)) && !any(isnan(v)) && !any(isinf(v));
    terms[GB_STAT_UNSTABLE] = finite && length(v) * kMore <= kUnstableSpeed ? 0.0 : 1.0;
    terms[GB_STAT_DEPTH] = -x.y;
    terms[GB_STAT_NEAR_LEFT] = -length(x - leftTip);
    terms[GB_STAT_NEAR_RIGHT] = -length(x - rightTip);
    if (voronoiArea[i] > 0.0) terms[GB_STAT_THIN] = -thickness[i];
    terms[GB_STAT_IMPACT] = hardestImpactOf(i, x, v);
  }
  const vec3 origin = steps[pc.stepIndex].volumeOrigin.xyz;
  for (uint k = triangleOffset[i]; k < triangleOffset[i + 1u]; ++k) {
    const uint t = triangleCorner[k] / 3u;
    const vec3 p0 = LOAD3(position, triangles[3u * t]), p1 = LOAD3(position, triangles[3u * t + 1u]);
    const vec3 p2 = LOAD3(position, triangles[3u * t + 2u]);
    const vec3 a = p0 - origin, b = p1 - origin, c = p2 - origin;
    terms[GB_STAT_AREA] += 0.5 * length(cross(b - a, c - a)) / 3.0;
    terms[GB_STAT_VOLUME] += dot(a, cross(b, c)) / 6.0 / 3.0;
    terms[GB_STAT_WINDING_LEFT] += windingOf(p0 - leftTip, p1 - leftTip, p2 - leftTip) / 3.0;
    terms[GB_STAT_WINDING_RIGHT] += windingOf(p0 - rightTip, p1 - rightTip, p2 - rightTip) / 3.0;
  }
  for (uint c = 0u; c < STATISTICS_TERMS; ++c) STATISTICS_A(c, i) = terms[c];
}
