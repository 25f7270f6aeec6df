#version 450
// Stage energy_budget, pass 1 (cpu-reference/solver/energy_budget.cpp, energyTerms): every particle's terms into half A
// of the budget's tree sum. Invocation 0 also keeps the bubble's volume before the step, which
// the host reduced just before (in half A of the volume's sum with GB_REDUCE_VOLUME_IN_A).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "energy.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (i == 0u) ENERGY_VOLUME_BEFORE = (pc.reduceFlags & GB_REDUCE_VOLUME_IN_A) != 0u ? REDUCE_A(0u) : REDUCE_B(0u);
  float terms[GB_ENERGY_TERMS];
  energyTerms(i, steps[pc.stepIndex].dt, steps[pc.stepIndex].closed != 0u, terms);
  for (uint c = 0u; c < ENERGY_TERMS; ++c) ENERGY_A(c, i) = terms[c];
}
