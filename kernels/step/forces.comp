#version 450
// forces (cpu-reference/stages/stages.cpp), the explicit integrator's forces: the whole of Eq. (2),
// internal + external + linear air drag.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "forces.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const StepUniformsBlock u = steps[pc.stepIndex];
  const vec3 drag = -params.airDrag * voronoiArea[i] * LOAD3(velocity, i);  // still air resists
  const float pressure = currentPressure(u);
  const vec3 n = LOAD3(normal, i);
  const vec3 coupling = -airCoupling(u, i) * dot(LOAD3(velocity, i), n) * n;  // the film moves with the air
  vec3 f = internalForce(i) + externalForce(u, pressure, i) + drag + coupling;
  if (u.closed != 0u) f += boyleForce(pressure, i);
  STORE3(force, i, f);
}
