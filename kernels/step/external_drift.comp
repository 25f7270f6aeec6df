#version 450
// Stage external_drift (cpu-reference/solver/implicit_euler.cpp, externalDrift): every particle's share of a closed
// film's drift, its mass and the explicit force on it (zero for a wire or dead particle), into the first blocks of half
// A of the energy budget's tree sum; energy_tree_sum (flag 2) sums them and implicit_predict reads the sums.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const bool moves = alive[i] != 0u && boundary[i] == 0u;
  const vec3 f = moves ? LOAD3(force, i) : vec3(0.0);
  ENERGY_A(0u, i) = moves ? mass[i] : 0.0;
  ENERGY_A(1u, i) = f.x;
  ENERGY_A(2u, i) = f.y;
  ENERGY_A(3u, i) = f.z;
}
