// Declarations every stage shares: the parameter block, the substep uniforms, push constants and the
// structure-of-arrays buffers, plus the functions of cpu-reference/stages.cpp that several stages need.
// Each function has the name and the float operations of its C++ twin.

#include "shared_params.h"
#include "shared_step.h"

layout(local_size_x_id = 0) in;
layout(push_constant) uniform Push { PushBlock pc; };

layout(std430, binding = GB_BINDING_PARAMS) readonly buffer ParamsBuffer { Params params; };
layout(std430, binding = GB_BINDING_STEPS) readonly buffer StepsBuffer { StepUniformsBlock steps[]; };
layout(std430, binding = GB_BINDING_POSITION) buffer PositionBuffer { float position[]; };
layout(std430, binding = GB_BINDING_VELOCITY) buffer VelocityBuffer { float velocity[]; };
layout(std430, binding = GB_BINDING_FORCE) buffer ForceBuffer { float force[]; };
layout(std430, binding = GB_BINDING_NORMAL) buffer NormalBuffer { float normal[]; };
layout(std430, binding = GB_BINDING_AIR_INFLOW) buffer AirInflowBuffer { float airInflow[]; };
layout(std430, binding = GB_BINDING_AIR_FLOW) buffer AirFlowBuffer { float airFlow[]; };
layout(std430, binding = GB_BINDING_AIR_FLOW_NEXT) buffer AirFlowNextBuffer { float airFlowNext[]; };
layout(std430, binding = GB_BINDING_MASS) readonly buffer MassBuffer { float mass[]; };
layout(std430, binding = GB_BINDING_LIQUID) buffer LiquidBuffer { float liquid[]; };
layout(std430, binding = GB_BINDING_VORONOI_AREA) buffer VoronoiAreaBuffer { float voronoiArea[]; };
layout(std430, binding = GB_BINDING_THICKNESS) buffer ThicknessBuffer { float thickness[]; };
layout(std430, binding = GB_BINDING_ELASTICITY) buffer ElasticityBuffer { float elasticity[]; };
layout(std430, binding = GB_BINDING_LIFETIME) buffer LifetimeBuffer { float lifetime[]; };
layout(std430, binding = GB_BINDING_FRAME_PARAM) readonly buffer FrameParamBuffer { float frameParam[]; };
layout(std430, binding = GB_BINDING_ALIVE) readonly buffer AliveBuffer { uint alive[]; };
layout(std430, binding = GB_BINDING_TRIANGLES) readonly buffer TrianglesBuffer { uint triangles[]; };
layout(std430, binding = GB_BINDING_REST_LENGTH) readonly buffer RestLengthBuffer { float restLength[]; };
layout(std430, binding = GB_BINDING_SPRING_OFFSET) readonly buffer SpringOffsetBuffer { uint springOffset[]; };
layout(std430, binding = GB_BINDING_SPRING_INDEX) readonly buffer SpringIndexBuffer { uint springIndex[]; };
layout(std430, binding = GB_BINDING_SPRING_NEIGHBOUR) readonly buffer SpringNeighbourBuffer { uint springNeighbour[]; };
layout(std430, binding = GB_BINDING_TRIANGLE_OFFSET) readonly buffer TriangleOffsetBuffer { uint triangleOffset[]; };
layout(std430, binding = GB_BINDING_TRIANGLE_CORNER) readonly buffer TriangleCornerBuffer { uint triangleCorner[]; };
layout(std430, binding = GB_BINDING_BOUNDARY) readonly buffer BoundaryBuffer { uint boundary[]; };
layout(std430, binding = GB_BINDING_REDUCE) buffer ReduceBuffer { float reduce[]; };
layout(std430, binding = GB_BINDING_DRAINAGE) buffer DrainageBuffer { float drainage[]; };
layout(std430, binding = GB_BINDING_TRIANGLE_NORMAL) buffer TriangleNormalBuffer { float triangleNormal[]; };
layout(std430, binding = GB_BINDING_CORNER_AREA) buffer CornerAreaBuffer { float cornerArea[]; };
layout(std430, binding = GB_BINDING_CONTACTS) readonly buffer ContactsBuffer { uint contacts[]; };
layout(std430, binding = GB_BINDING_PREVIOUS_POSITION) buffer PreviousPositionBuffer { float previousPosition[]; };
layout(std430, binding = GB_BINDING_COLOUR_ORDER) readonly buffer ColourOrderBuffer { uint colourOrder[]; };

// The two halves of the reduce buffer (tree sum ping-pong) and of the drainage buffer.
#define REDUCE_A(k) reduce[(k)]
#define REDUCE_B(k) reduce[pc.triangles + (k)]
// The energy budget's part of the reduce buffer, from pc.first (after the coarse correction's): halves A and B of
// its tree sum, each ENERGY_TERMS blocks of `particles` floats (ParticleEnergy of energy_budget.h, GB_ENERGY_TERMS of
// shared_step.h), then the bubble's volume before the step and the VelocityBudget (scale, centre, shift, released).
#define ENERGY_TERMS uint(GB_ENERGY_TERMS)
#define DRIFT_TERMS uint(GB_DRIFT_TERMS)  // external_drift's terms, in the first blocks (energy_tree_sum's flag 2)
#define ENERGY_A(c, k) reduce[pc.first + (c)*pc.particles + (k)]
#define ENERGY_B(c, k) reduce[pc.first + (ENERGY_TERMS + (c)) * pc.particles + (k)]
#define ENERGY_SLOT(k) reduce[pc.first + 2u * ENERGY_TERMS * pc.particles + (k)]
#define ENERGY_VOLUME_BEFORE ENERGY_SLOT(0u)
#define ENERGY_VELOCITY_SCALE ENERGY_SLOT(1u)
#define ENERGY_CENTRE vec3(ENERGY_SLOT(2u), ENERGY_SLOT(3u), ENERGY_SLOT(4u))
#define ENERGY_SHIFT vec3(ENERGY_SLOT(5u), ENERGY_SLOT(6u), ENERGY_SLOT(7u))
#define ENERGY_RELEASED ENERGY_SLOT(8u)
#define DRAIN_OUTFLOW(i) drainage[(i)]
#define DRAIN_WEIGHT(i) drainage[pc.particles + (i)]

// Vector attribute access: x, y, z blocks of pc.particles floats each.
#define LOAD3(buf, i) vec3(buf[(i)], buf[pc.particles + (i)], buf[2u * pc.particles + (i)])
#define STORE3(buf, i, v)                    \
  {                                          \
    const vec3 value_ = (v);                 \
    buf[(i)] = value_.x;                     \
    buf[pc.particles + (i)] = value_.y;      \
    buf[2u * pc.particles + (i)] = value_.z; \
  }

// contactRestDistance: the rest distance of the k-th partner entry, stored after the partners (C++ twin).
float contactRestDistance(uint k) { return uintBitsToFloat(contacts[pc.particles + 1u + contacts[pc.particles] + k]); }

// positionAtStepStart of cpu-reference/energy_budget.cpp: x_t, or where the wire put a wire particle.
vec3 positionAtStepStart(uint i) { return boundary[i] != 0u ? LOAD3(position, i) : LOAD3(previousPosition, i); }

// triangleAreaAtStart of cpu-reference/energy_budget.cpp: triangle t's area at the step's start.
float triangleAreaAtStart(uint t) {
  const vec3 a0 = positionAtStepStart(triangles[3u * t]);
  return 0.5 * length(cross(positionAtStepStart(triangles[3u * t + 1u]) - a0,
                            positionAtStepStart(triangles[3u * t + 2u]) - a0));
}

// triangleTensionOf of cpu-reference/implicit_euler.cpp: the physical model's tension of a triangle at `area`,
// Gibbs's law in its own area from the tension and area it had at the step's start, and its slope dT/dA.
struct TriangleTension {
  float tension, slope;
};
TriangleTension triangleTensionOf(float startTension, float startArea, float area) {
  const float gibbs = params.gibbsElasticity, lowest = params.surfaceTension, highest = 4.0 * params.surfaceTension;
  const bool follows = 0.0 < gibbs && 0.0 < startArea && 0.0 < area;
  const float unclamped = startTension + gibbs * log(follows ? area / startArea : 1.0);
  const bool elastic = follows && lowest < unclamped && unclamped < highest;
  return TriangleTension(follows ? min(max(unclamped, lowest), highest) : startTension, elastic ? gibbs / area : 0.0);
}

// triangleTensionEnergy of cpu-reference/implicit_euler.cpp (there in double).
float triangleTensionEnergy(float startTension, float startArea, float area) {
  const float gibbs = params.gibbsElasticity, t0 = startTension, a0 = startArea;
  if (!(gibbs > 0.0 && a0 > 0.0 && area > 0.0)) return t0 * area;
  const float r = area / a0, lnR = log(r), unclamped = t0 + gibbs * lnR;
  const float lowest = params.surfaceTension, highest = 4.0 * params.surfaceTension;
  if (lowest <= unclamped && unclamped <= highest) return t0 * area + gibbs * a0 * (r * lnR - r + 1.0);
  const float held = unclamped < lowest ? lowest : highest, lnReached = (held - t0) / gibbs;
  const float reached = exp(lnReached);
  return t0 * a0 * reached + gibbs * a0 * (reached * lnReached - reached + 1.0) + held * (area - a0 * reached);
}

// framePoint of cpu-reference/wire_frame.cpp.
vec3 framePoint(StepUniformsBlock u, float param) {
  const float pi = 3.14159265358979323846;
  if (u.frameKind == 0 && param < 1.0)
    return u.frameCenter.xyz + (2.0 * param - 1.0) * u.frameHalfWidth * u.frameAxis.xyz;
  const float phi = u.frameKind == 0 ? (param - 1.0) * pi : 2.0 * pi * param;
  return u.frameCenter.xyz + u.frameHalfWidth * cos(phi) * u.frameAxis.xyz + u.frameDepth * sin(phi) * u.frameDown.xyz;
}

// drainageDirection of cpu-reference/stages.cpp, Eq. (14).
float drainageDirection(vec3 xi, vec3 xj, vec3 g) {
  const vec3 d = xj - xi;
  const float along = dot(d, g);
  return along > 0.0 ? along / (length(d) * length(g)) : 0.0;
}

// boylePressure of cpu-reference/stages.cpp, Eq. (11).
float boylePressure(float referenceVolume, float currentVolume) {
  return currentVolume > 0.0 ? params.pressureCoefficient * referenceVolume / currentVolume
                             : params.pressureCoefficient;
}
