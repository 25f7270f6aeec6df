#version 450
// airInflow (cpu-reference/stages/stages.cpp): Eq. (5), the air flow the moving wands push at particle i.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const StepUniformsBlock u = steps[pc.stepIndex];
  const vec3 x = LOAD3(position, i);
  const float dLeft = length(x - u.leftPosition.xyz), dRight = length(x - u.rightPosition.xyz);
  const vec3 sources = u.leftInflowWeight * u.leftVelocity.xyz / (dLeft + params.airInflowDistance) +
                       u.rightVelocity.xyz / (dRight + params.airInflowDistance);
  STORE3(airInflow, i, -u.airVolume * u.wandAlignment * sources);
}
