#version 450
// implicitPredict (cpu-reference/solver/implicit_euler.cpp): keeps x_t, places the wire's particles on the wire
// frame at the end of the step, starts an interior particle from x_t + h v_t + h^2 a above the floor, a a closed
// film's drift from external_drift's sums (in half A of the energy terms with GB_REDUCE_ENERGY_IN_A).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

// driftAcceleration of cpu-reference/solver/implicit_euler.cpp: sum f / sum m, zero without mass.
vec3 driftAcceleration(float mass, vec3 force) { return mass > 0.0 ? force / mass : vec3(0.0); }

// CpuStepper::filmDrift's result: the drift from the sums that external_drift's tree sum left.
vec3 filmDrift() {
  const bool inA = (pc.reduceFlags & GB_REDUCE_ENERGY_IN_A) != 0u;
  const float m = inA ? ENERGY_A(0u, 0u) : ENERGY_B(0u, 0u);
  const vec3 f = inA ? vec3(ENERGY_A(1u, 0u), ENERGY_A(2u, 0u), ENERGY_A(3u, 0u))
                     : vec3(ENERGY_B(1u, 0u), ENERGY_B(2u, 0u), ENERGY_B(3u, 0u));
  return driftAcceleration(m, f);
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (alive[i] == 0u) return;
  const StepUniformsBlock u = steps[pc.stepIndex];
  const vec3 x = LOAD3(position, i);
  STORE3(previousPosition, i, x);
  if (boundary[i] != 0u) {
    if (wireParam[i] >= 0.0) STORE3(position, i, wirePoint(u, wireParam[i]));
    return;
  }
  const vec3 drift = u.closed != 0u ? filmDrift() : vec3(0.0);
  vec3 guess = x + u.dt * LOAD3(velocity, i) + (u.dt * u.dt) * drift;
  guess.y = max(guess.y, 0.0);  // the floor, y = 0
  STORE3(position, i, guess);
}
