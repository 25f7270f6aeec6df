#version 450
// filmFlowVelocity (cpu-reference/stages/stages.cpp): film flow pass 1, the liquid's new velocity from its terms
// (filmFlowTerms), Jacobi-implicit in their rates. Each ln Gamma is computed where it is read (the CPU's pass 0,
// filmFlowLogSurfactant, keeps one a particle).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

vec3 tangential(vec3 v, vec3 n) { return v - dot(v, n) * n; }

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  FLOW(flowAreaShareBlock, i) = flowAreaShare(i);  // once here, not in each of the ring's swept areas after
  if (alive[i] == 0u || boundary[i] != 0u) {
    storeFlow3(flowVelocityNextBlock, i, vec3(0.0));
    return;
  }
  const StepUniformsBlock u = steps[pc.stepIndex];
  const vec3 n = LOAD3(normal, i), xi = LOAD3(position, i);
  const float e = max(thickness[i], kThinnestFlowingFilm), rho = params.liquidDensity;
  const float logSurfactantI = logSurfactant(FLOW(surfactantBlock, i), thickness[i]);
  vec3 gradient = vec3(0.0), pull = vec3(0.0);
  float weight = 0.0, neighbours = 0.0;
  for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
    const uint j = springNeighbour[k];
    if (alive[j] == 0u) continue;
    const vec3 d = LOAD3(position, j) - xi;
    const float d2 = dot(d, d);
    if (!(d2 > 0.0)) continue;
    gradient += (logSurfactant(FLOW(surfactantBlock, j), thickness[j]) - logSurfactantI) / d2 * d;
    pull += loadFlow3(flowVelocityBlock, j) / d2;
    weight += 1.0 / d2;
    neighbours += 1.0;
  }
  const vec3 gravity = tangential(vec3(params.gravityX, params.gravityY, params.gravityZ), n);
  vec3 marangoni = vec3(0.0), viscosityPull = vec3(0.0);
  float viscosityRate = 0.0, spacingSquared = 0.0;
  if (neighbours > 0.0) {
    marangoni = -(params.marangoniElasticity / (rho * e)) * tangential((2.0 / neighbours) * gradient, n);
    viscosityRate = params.flowViscosity * (4.0 / neighbours) * weight;
    viscosityPull = params.flowViscosity * (4.0 / neighbours) * pull;
    spacingSquared = neighbours / weight;
  }
  const vec3 airVelocity = u.wireArea > 0.0 ? LOAD3(airFlow, i) / u.wireArea : vec3(0.0);
  const vec3 air = tangential(airVelocity - LOAD3(velocity, i), n);
  const float airRate = 2.0 * params.airShear / (rho * e);
  const float wallRate = 12.0 * params.liquidViscosity * params.surfaceRigidity / (rho * e * e);
  const float dt = u.drainageDt;
  const float held = 1.0 + dt * (airRate + wallRate + viscosityRate);
  const float diffused = params.marangoniElasticity / (rho * e) * dt / held * dt;
  const float capped = kMarangoniCourant * spacingSquared;
  const float c = diffused > capped ? capped / diffused : 1.0;
  const vec3 driven = loadFlow3(flowVelocityBlock, i) + dt * (gravity + c * marangoni + airRate * air + viscosityPull);
  storeFlow3(flowVelocityNextBlock, i, tangential(driven / held, n));
}
