#version 450
// Stage energy_budget, pass 3 (CpuStepper's budgetEnergy): one invocation turns the sums into the VelocityBudget,
// with a closed bubble's gas change between the kept volume before the step and the one just reduced.
// GB_REDUCE_ENERGY_IN_A: the sums are in half A; GB_REDUCE_VOLUME_IN_A: the volume after is in half A of its sum.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "energy.glsl"

void main() {
  if (gl_GlobalInvocationID.x != 0u) return;
  const bool sumsInA = (pc.reduceFlags & GB_REDUCE_ENERGY_IN_A) != 0u;
  float sums[GB_ENERGY_TERMS];
  for (uint c = 0u; c < ENERGY_TERMS; ++c) sums[c] = sumsInA ? ENERGY_A(c, 0u) : ENERGY_B(c, 0u);
  const StepUniformsBlock u = steps[pc.stepIndex];
  float gas = 0.0;
  if (u.closed != 0u) {
    const float after = (pc.reduceFlags & GB_REDUCE_VOLUME_IN_A) != 0u ? REDUCE_A(0u) : REDUCE_B(0u);
    gas = boyleEnergyChange(u.referenceVolume, ENERGY_VOLUME_BEFORE, after);
  }
  float scale, released;
  vec3 centre, shift;
  energyScale(sums[0], sums[1], sums[2] + gas, sums[3], vec3(sums[4], sums[5], sums[6]),
              vec3(sums[7], sums[8], sums[9]), scale, centre, shift, released);
  ENERGY_VELOCITY_SCALE = scale;
  for (int c = 0; c < 3; ++c) {
    ENERGY_SLOT(GB_SLOT_CENTRE + c) = centre[c];
    ENERGY_SLOT(GB_SLOT_SHIFT + c) = shift[c];
  }
  ENERGY_RELEASED = released;
}
