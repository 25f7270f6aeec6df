#version 450
// vertexBlockDescent (cpu-reference/solver/implicit_euler.cpp) for the particles of one colour: one Newton step of
// the implicit objective in x_i alone, then the floor. The host dispatches the colours in order; no two
// particles of a colour are coupled, so they read only settled neighbours.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "forces.glsl"
#include "vertex_block.glsl"

void main() {
  const uint k = gl_GlobalInvocationID.x;
  if (k >= pc.count) return;
  const uint i = colourOrder[pc.first + k];
  if (alive[i] == 0u) return;  // died in a burst since the colouring was made
  objectiveBlock(steps[pc.stepIndex], i);
  const vec3 step = solveLinear3(hessian, gradient);
  if (any(isnan(step)) || any(isinf(step))) return;
  vec3 next = LOAD3(position, i) - withinTrustRegion(step, shortestSpring);
  next.y = max(next.y, 0.0);
  STORE3(position, i, next);
}
