#version 450
// triangleVolume (cpu-reference/stages/stages.cpp) for every triangle, into the reduce buffer's half A: the leaves of
// the volume's tree sum. GB_REDUCE_AT_STEP_START: at the step's start instead (triangleVolumeAtStart, the energy
// budget).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

vec3 corner(uint i) {
  return (pc.reduceFlags & GB_REDUCE_AT_STEP_START) != 0u ? positionAtStepStart(i) : LOAD3(position, i);
}

void main() {
  const uint t = gl_GlobalInvocationID.x;
  if (t >= pc.count) return;
  const vec3 origin = steps[pc.stepIndex].volumeOrigin.xyz;
  const vec3 a = corner(triangles[3u * t]) - origin;
  const vec3 b = corner(triangles[3u * t + 1u]) - origin;
  const vec3 c = corner(triangles[3u * t + 2u]) - origin;
  REDUCE_A(t) = dot(a, cross(b, c)) / 6.0;
}
