#version 450
// Stage energy_budget, pass 3 (CpuStepper's budgetEnergy): one invocation turns the sums into the VelocityBudget,
// with a closed bubble's gas change between the kept volume before the step and the one just reduced.
// pc.reduceFlags bit 1: the sums are in half A; bit 2: the volume after is in half A of the volume's sum.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "energy.glsl"

void main() {
  if (gl_GlobalInvocationID.x != 0u) return;
  const bool sumsInA = (pc.reduceFlags & 1u) != 0u;
  float sums[GB_ENERGY_TERMS];
  for (uint c = 0u; c < ENERGY_TERMS; ++c) sums[c] = sumsInA ? ENERGY_A(c, 0u) : ENERGY_B(c, 0u);
  const StepUniformsBlock u = steps[pc.stepIndex];
  float gas = 0.0;
  if (u.closed != 0u) {
    const float after = (pc.reduceFlags & 2u) != 0u ? REDUCE_A(0u) : REDUCE_B(0u);
    gas = boyleEnergyChange(u.referenceVolume, ENERGY_VOLUME_BEFORE, after);
  }
  float scale, released;
  vec3 centre, shift;
  energyBudget(sums[0], sums[1], sums[2] + gas, sums[3], vec3(sums[4], sums[5], sums[6]),
               vec3(sums[7], sums[8], sums[9]), scale, centre, shift, released);
  ENERGY_VELOCITY_SCALE = scale;
  ENERGY_SLOT(2u) = centre.x;
  ENERGY_SLOT(3u) = centre.y;
  ENERGY_SLOT(4u) = centre.z;
  ENERGY_SLOT(5u) = shift.x;
  ENERGY_SLOT(6u) = shift.y;
  ENERGY_SLOT(7u) = shift.z;
  ENERGY_SLOT(8u) = released;
}
