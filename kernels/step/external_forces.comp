#version 450
// externalForces (cpu-reference/stages/stages.cpp), the implicit integrator's explicit forces: gravity and
// the air (drag and the internal forces are in the solver).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "forces.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const StepUniformsBlock u = steps[pc.stepIndex];
  STORE3(force, i, externalForce(u, currentPressure(u), i));
}
