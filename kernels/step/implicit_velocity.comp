#version 450
// implicitVelocity (cpu-reference/solver/implicit_euler.cpp): the implicit Euler velocity v = (x - x_t) / h, a free
// particle's as the energy budget leaves it (kept at pc.first's region of the reduce buffer).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "energy.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (alive[i] == 0u) return;
  const vec3 v = (LOAD3(position, i) - LOAD3(previousPosition, i)) / steps[pc.stepIndex].dt;
  if (boundary[i] != 0u || params.energyBudget == 0) {
    STORE3(velocity, i, v);
  } else {
    STORE3(velocity, i, budgetedVelocity(ENERGY_VELOCITY_SCALE, ENERGY_CENTRE, ENERGY_SHIFT, v));
  }
}
