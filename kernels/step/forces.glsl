// The force functions of cpu-reference/stages/stages.cpp that forces.comp and external_forces.comp share, each
// with the name and the float operations of its C++ twin. Include after common.glsl.

// areaTensionForce: -sum_t T_t grad_i A_t over i's triangles (physical model).
vec3 areaTensionForce(uint i) {
  vec3 f = vec3(0.0);
  for (uint k = triangleOffset[i]; k < triangleOffset[i + 1u]; ++k) {
    const uint corner = triangleCorner[k], t = corner / 3u, c = corner % 3u;
    const uint j = triangles[3u * t + (c + 1u) % 3u], l = triangles[3u * t + (c + 2u) % 3u];
    const vec3 twiceAreaNormal =
        vec3(triangleNormal[t], triangleNormal[pc.triangles + t], triangleNormal[2u * pc.triangles + t]);
    const float twiceArea = length(twiceAreaNormal);
    if (twiceArea <= 0.0) continue;
    const float tension =
        (elasticity[triangles[3u * t]] + elasticity[triangles[3u * t + 1u]] + elasticity[triangles[3u * t + 2u]]) / 3.0;
    f -= tension * 0.5 * cross(twiceAreaNormal / twiceArea, LOAD3(position, l) - LOAD3(position, j));
  }
  return f;
}

// internalForce: surface tension (Eq. 3 or the area tension), spring damping (Algorithm 1), contacts.
vec3 internalForce(uint i) {
  const vec3 xi = LOAD3(position, i), vi = LOAD3(velocity, i);
  const float ei = elasticity[i];
  const bool physical = params.tensionModel == 1;
  vec3 f = physical ? areaTensionForce(i) : vec3(0.0);
  for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
    const uint j = springNeighbour[k];
    const vec3 d = LOAD3(position, j) - xi;
    const float len = length(d);
    if (len <= 0.0) continue;
    const vec3 dir = d / len;
    const float stiffness = 0.5 * (ei + elasticity[j]);
    if (!physical) f += stiffness * (len - restLength[springIndex[k]]) * dir;  // Eq. (3)
    f += params.springDamping * dot(LOAD3(velocity, j) - vi, dir) * dir;       // Algorithm 1, line 5
  }
  // Self-collision contacts (packed: offsets, neighbours from pc.particles + 1, then their rest distances).
  const uint base = pc.particles + 1u;
  for (uint k = contacts[i]; k < contacts[i + 1u]; ++k) {
    const uint j = contacts[base + k];
    const vec3 d = xi - LOAD3(position, j);
    const float len = length(d), rest = contactRestDistance(k);
    if (!(len > 0.0 && len < rest)) continue;
    const vec3 away = d / len;
    const float approach = dot(vi - LOAD3(velocity, j), away);
    f += params.collisionStiffness * (rest - len) * away;
    if (approach < 0.0) f -= params.collisionDamping * approach * away;
  }
  return f;
}

// The volume the last tree sum left in half A or B (GB_REDUCE_VOLUME_IN_A).
float currentVolume() { return (pc.reduceFlags & GB_REDUCE_VOLUME_IN_A) != 0u ? REDUCE_A(0u) : REDUCE_B(0u); }

// The Boyle pressure at that volume (P_0 for an open film).
float currentPressure(StepUniformsBlock u) {
  if (u.closed == 0u) return params.pressureCoefficient;
  return boylePressure(u.referenceVolume, currentVolume());
}

// liquidMass (cpu-reference/model/film.h): the mass gravity pulls on, the particle's liquid.
float liquidMass(uint i) { return params.liquidDensity * liquid[i]; }

// externalForce: gravity (less a free bubble's lift), and the air force, Eq. (9) open or Eqs. (10)-(11) closed.
vec3 externalForce(StepUniformsBlock u, float pressure, uint i) {
  const vec3 n = LOAD3(normal, i);
  const float area = voronoiArea[i];
  const float lifted = u.closed != 0u ? params.bubbleLift : 0.0;  // a free bubble's air may carry some of its weight
  vec3 f = (1.0 - lifted) * liquidMass(i) * vec3(params.gravityX, params.gravityY, params.gravityZ);
  const float flowIn = dot(LOAD3(airFlow, i), n), directIn = dot(LOAD3(airInflow, i), n);
  if (u.closed != 0u) {
    f += pressure / params.pressureCoefficient * params.airPressureGain * flowIn * area * n;  // Eq. (10), air
  } else {
    f += params.airPressureGain * (flowIn + directIn) * area * n;  // Eq. (9)
  }
  return f;
}

// airCoupling: kappa Area_wm A_Vor on an open film, the damping of its normal speed towards the air's.
float airCoupling(StepUniformsBlock u, uint i) {
  if (u.closed != 0u || !(u.wireArea > 0.0)) return 0.0;
  const float airSpeed = abs(dot(LOAD3(airFlow, i) + LOAD3(airInflow, i), LOAD3(normal, i))) / u.wireArea;
  return params.airPressureGain * u.wireArea * voronoiArea[i] * min(1.0, airSpeed / kStillAirSpeed);
}

// volumeGradient: a sixth of the twice-area normals of particle i's triangles.
vec3 volumeGradient(uint i) {
  vec3 twiceAreaNormals = vec3(0.0);
  for (uint k = triangleOffset[i]; k < triangleOffset[i + 1u]; ++k) {
    const uint t = triangleCorner[k] / 3u;
    twiceAreaNormals +=
        vec3(triangleNormal[t], triangleNormal[pc.triangles + t], triangleNormal[2u * pc.triangles + t]);
  }
  return twiceAreaNormals / 6.0;
}

// boyleForce: the excess of Boyle's pressure over P_0 times the volume's gradient, Eqs. (10)-(11).
vec3 boyleForce(float pressure, uint i) { return (pressure - params.pressureCoefficient) * volumeGradient(i); }
