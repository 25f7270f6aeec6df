#version 450
// predictImplicitStep (cpu-reference/implicit_euler.cpp): keeps x_t, places the wire's particles on the wire
// frame at the end of the step, starts an interior particle from x_t + h v_t above the floor.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (alive[i] == 0u) return;
  const StepUniformsBlock u = steps[pc.stepIndex];
  const vec3 x = LOAD3(position, i);
  STORE3(previousPosition, i, x);
  if (boundary[i] != 0u) {
    if (frameParam[i] >= 0.0) STORE3(position, i, framePoint(u, frameParam[i]));
    return;
  }
  vec3 guess = x + u.dt * LOAD3(velocity, i);
  guess.y = max(guess.y, 0.0);  // the floor, y = 0
  STORE3(position, i, guess);
}
