// Declarations every stage shares: the parameter block, the step uniforms, push constants and the
// structure-of-arrays buffers, plus the functions of cpu-reference/stages/stages.cpp that several stages need.
// Each function has the name and the float operations of its C++ twin.

#include "shared_formulas.h"
#include "shared_params.h"
#include "shared_step.h"

layout(local_size_x_id = 0) in;
layout(push_constant) uniform Push { PushBlock pc; };

// The storage buffers, declared from their one list (device_data.h).
#define GB_WRITABLE
#define GB_BUFFER(b, NAME, element, declarator, access) \
  layout(std430, binding = b) access buffer NAME##_BUFFER { element declarator; };
#define GB_PARTICLE_ARRAY(b, NAME, name, components, element, access, transfer, created) \
  layout(std430, binding = b) access buffer NAME##_BUFFER { element name[]; };
#define GB_PARTICLE_BLOCK(NAME, block, name, components, transfer, created) const uint name##Block = block;
#include "device_data.h"
#undef GB_BUFFER
#undef GB_PARTICLE_ARRAY
#undef GB_PARTICLE_BLOCK

// The reduce buffer's regions (shared_step.h). The volume's tree sum, halves A and B:
#define REDUCE_A(k) reduce[(k)]
#define REDUCE_B(k) reduce[reduceHalfB(pc.triangles) + (k)]
// The energy budget's terms from pc.first on, halves A and B of ENERGY_TERMS blocks of `particles` floats each
// (ParticleEnergy of energy_budget.h); external_drift's DRIFT_TERMS use the first blocks. Then the slots.
#define ENERGY_TERMS uint(GB_ENERGY_TERMS)
#define DRIFT_TERMS uint(GB_DRIFT_TERMS)
#define ENERGY_A(c, k) reduce[pc.first + (c)*pc.particles + (k)]
#define ENERGY_B(c, k) reduce[pc.first + (ENERGY_TERMS + (c)) * pc.particles + (k)]
#define ENERGY_SLOT(k) reduce[reduceEnergySlotsAt(pc.first, pc.particles) + uint(k)]
#define ENERGY_VOLUME_BEFORE ENERGY_SLOT(GB_SLOT_VOLUME_BEFORE)
#define ENERGY_VELOCITY_SCALE ENERGY_SLOT(GB_SLOT_SCALE)
#define ENERGY_CENTRE \
  vec3(ENERGY_SLOT(GB_SLOT_CENTRE), ENERGY_SLOT(GB_SLOT_CENTRE + 1), ENERGY_SLOT(GB_SLOT_CENTRE + 2))
#define ENERGY_SHIFT vec3(ENERGY_SLOT(GB_SLOT_SHIFT), ENERGY_SLOT(GB_SLOT_SHIFT + 1), ENERGY_SLOT(GB_SLOT_SHIFT + 2))
#define ENERGY_RELEASED ENERGY_SLOT(GB_SLOT_RELEASED)
// The frame's statistics terms from pc.first on (reduceStatisticsAt), halves A and B of GB_STATISTICS_TERMS blocks.
#define STATISTICS_TERMS uint(GB_STATISTICS_TERMS)
#define STATISTICS_A(c, k) reduce[pc.first + (c)*pc.particles + (k)]
#define STATISTICS_B(c, k) reduce[pc.first + (STATISTICS_TERMS + (c)) * pc.particles + (k)]
// The drainage passes' two arrays (drainOutflowBlock, drainWeightBlock from device_data.h).
#define DRAIN_OUTFLOW(i) drainage[drainOutflowBlock * pc.particles + (i)]
#define DRAIN_WEIGHT(i) drainage[drainWeightBlock * pc.particles + (i)]

// A per-particle array of the drainage buffer from its block on (device_data.h): one float, or x, y and z blocks.
#define FLOW(block, i) drainage[(block)*pc.particles + (i)]
vec3 loadFlow3(uint block, uint i) { return vec3(FLOW(block, i), FLOW(block + 1u, i), FLOW(block + 2u, i)); }
void storeFlow3(uint block, uint i, vec3 v) {
  FLOW(block, i) = v.x;
  FLOW(block + 1u, i) = v.y;
  FLOW(block + 2u, i) = v.z;
}

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

// positionAtStepStart of cpu-reference/solver/energy_budget.cpp: x_t, or where the wire put a wire particle.
vec3 positionAtStepStart(uint i) { return boundary[i] != 0u ? LOAD3(position, i) : LOAD3(previousPosition, i); }

// triangleAreaAtStart of cpu-reference/solver/energy_budget.cpp: triangle t's area at the step's start.
float triangleAreaAtStart(uint t) {
  const vec3 a0 = positionAtStepStart(triangles[3u * t]);
  return 0.5 * length(cross(positionAtStepStart(triangles[3u * t + 1u]) - a0,
                            positionAtStepStart(triangles[3u * t + 2u]) - a0));
}

// triangleTensionOf of cpu-reference/solver/implicit_euler.cpp: the physical model's tension of a triangle at `area`,
// Gibbs's law in its own area from the tension and area it had at the step's start, and its slope dT/dA.
struct TriangleTension {
  float tension, slope;
};
TriangleTension triangleTensionOf(float startTension, float startArea, float area) {
  const float gibbs = params.gibbsElasticity, lowest = lowestTension(params.surfaceTension),
              highest = highestTension(params.surfaceTension);
  const bool follows = 0.0 < gibbs && 0.0 < startArea && 0.0 < area;
  const float unclamped = startTension + gibbs * log(follows ? area / startArea : 1.0);
  const bool elastic = follows && lowest < unclamped && unclamped < highest;
  return TriangleTension(follows ? min(max(unclamped, lowest), highest) : startTension, elastic ? gibbs / area : 0.0);
}

// triangleTensionEnergy of cpu-reference/solver/implicit_euler.cpp (there in double).
float triangleTensionEnergy(float startTension, float startArea, float area) {
  const float gibbs = params.gibbsElasticity, t0 = startTension, a0 = startArea;
  if (!(gibbs > 0.0 && a0 > 0.0 && area > 0.0)) return t0 * area;
  const float r = area / a0, lnR = log(r), unclamped = t0 + gibbs * lnR;
  const float lowest = lowestTension(params.surfaceTension), highest = highestTension(params.surfaceTension);
  if (lowest <= unclamped && unclamped <= highest) return t0 * area + gibbs * a0 * (r * lnR - r + 1.0);
  const float held = unclamped < lowest ? lowest : highest, lnReached = (held - t0) / gibbs;
  const float reached = exp(lnReached);
  return t0 * a0 * reached + gibbs * a0 * (reached * lnReached - reached + 1.0) + held * (area - a0 * reached);
}

// wirePoint of cpu-reference/model/wire_frame.cpp.
vec3 wirePoint(StepUniformsBlock u, float param) {
  const float pi = 3.14159265358979323846;
  if (u.wireKind == 0 && param < 1.0) return u.wireCenter.xyz + (2.0 * param - 1.0) * u.wireHalfWidth * u.wireAxis.xyz;
  const float phi = u.wireKind == 0 ? (param - 1.0) * pi : 2.0 * pi * param;
  return u.wireCenter.xyz + u.wireHalfWidth * cos(phi) * u.wireAxis.xyz + u.wireDepth * sin(phi) * u.wireDown.xyz;
}

// drainageDirection of cpu-reference/stages/stages.cpp, Eq. (14).
float drainageDirection(vec3 xi, vec3 xj, vec3 g) {
  const vec3 d = xj - xi;
  const float along = dot(d, g);
  return along > 0.0 ? along / (length(d) * length(g)) : 0.0;
}

// boylePressure of cpu-reference/stages/stages.cpp, Eq. (11).
float boylePressure(float referenceVolume, float currentVolume) {
  return currentVolume > 0.0 ? params.pressureCoefficient * referenceVolume / currentVolume
                             : params.pressureCoefficient;
}

// logSurfactant of cpu-reference/stages/stages.cpp: ln(Gamma / Gamma_0), of order one.
float logSurfactant(float surfactant, float thickness) {
  return log(max(surfactant, kLeastSurfactant) *
             (max(thickness, kThinnestFlowingFilm) / initialThicknessOf(params.areaWeight)));
}

// flowAreaShare of cpu-reference/stages/stages.cpp: A_i / k_i, particle i's area per spring.
float flowAreaShare(uint i) {
  const uint springs = springOffset[i + 1u] - springOffset[i];
  return springs > 0u ? voronoiArea[i] / float(springs) : 0.0;
}
// filmFlowSweptArea of cpu-reference/stages/stages.cpp: flowSweptArea of i towards j, i's new velocity, the shares
// pass 1 stored.
float filmFlowSweptArea(float dt, uint i, uint j) {
  const vec3 d = LOAD3(position, j) - LOAD3(position, i);
  const float d2 = dot(d, d);
  if (!(d2 > 0.0)) return 0.0;
  return flowSweptArea(dt, FLOW(flowAreaShareBlock, i), FLOW(flowAreaShareBlock, j),
                       dot(loadFlow3(flowVelocityNextBlock, i), d), d2);
}

// filmFlowSent of cpu-reference/stages/stages.cpp: the liquid i sends to j in dt, its swept area times e_i and its
// limit.
float filmFlowSent(float dt, uint i, uint j) {
  return filmFlowSweptArea(dt, i, j) * thickness[i] * FLOW(flowLimitBlock, i);
}
