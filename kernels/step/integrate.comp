#version 450
// integrate (cpu-reference/stages/stages.cpp): semi-implicit Euler, Eqs. (12)-(13); boundary particles
// are carried to the wire frame at the end of the substep.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (alive[i] == 0u) return;
  const StepUniformsBlock u = steps[pc.stepIndex];
  const vec3 x = LOAD3(position, i);
  if (boundary[i] != 0u) {
    if (wireParam[i] < 0.0) {  // pinned where it is (the fixed rings of the validation scenes)
      STORE3(velocity, i, vec3(0.0));
      return;
    }
    const vec3 xNext = wirePoint(u, wireParam[i]);
    STORE3(velocity, i, (xNext - x) / u.dt);
    STORE3(position, i, xNext);
    return;
  }
  vec3 v = LOAD3(velocity, i) + u.dt * LOAD3(force, i) / mass[i];  // Eq. (12)
  vec3 xNew = x + u.dt * v;                                        // Eq. (13)
  if (xNew.y < 0.0) {  // the floor, y = 0: the film lands and slides, it does not pass through
    xNew.y = 0.0;
    v.y = max(v.y, 0.0);
  }
  STORE3(velocity, i, v);
  STORE3(position, i, xNew);
}
