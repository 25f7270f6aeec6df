#version 450
// finishImplicitStep (cpu-reference/implicit_euler.cpp): the implicit Euler velocity v = (x - x_t) / h.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (alive[i] == 0u) return;
  STORE3(velocity, i, (LOAD3(position, i) - LOAD3(previousPosition, i)) / steps[pc.stepIndex].dt);
}
