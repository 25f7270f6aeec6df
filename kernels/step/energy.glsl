// The implicit step's energy budget (cpu-reference/solver/energy_budget.h): each function has its C++ twin's name and
// float operations.

// heldShares: particle i's share of the internal energy at the step's start and at its end, in one pass over its
// one-ring: half of each spring (a third of each triangle) and half of each contact's penalty.
void heldShares(uint i, out float start, out float end) {
  const vec3 xi = LOAD3(position, i), xi0 = positionAtStepStart(i);
  start = 0.0;
  end = 0.0;
  if (params.tensionModel == 1) {
    for (uint k = triangleOffset[i]; k < triangleOffset[i + 1u]; ++k) {
      const uint t = triangleCorner[k] / 3u;
      const uint c0 = triangles[3u * t], c1 = triangles[3u * t + 1u], c2 = triangles[3u * t + 2u];
      const float tension = (elasticity[c0] + elasticity[c1] + elasticity[c2]) / 3.0, area0 = triangleAreaAtStart(t);
      const vec3 a = LOAD3(position, c0);
      const float area = 0.5 * length(cross(LOAD3(position, c1) - a, LOAD3(position, c2) - a));
      start += tension * area0 / 3.0;
      end += triangleTensionEnergy(tension, area0, area) / 3.0;
    }
  } else {
    for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
      const uint j = springNeighbour[k];
      const float stiffness = 0.5 * (elasticity[i] + elasticity[j]), rest = restLength[springIndex[k]];
      const float stretch0 = length(positionAtStepStart(j) - xi0) - rest;
      const float stretch = length(LOAD3(position, j) - xi) - rest;
      start += 0.5 * springEnergyOf(stiffness, stretch0);  // each end's half
      end += 0.5 * springEnergyOf(stiffness, stretch);
    }
  }
  const uint base = pc.particles + 1u;
  for (uint k = contacts[i]; k < contacts[i + 1u]; ++k) {
    const uint j = contacts[base + k];
    const float rest = contactRestDistance(k);
    const float len0 = length(xi0 - positionAtStepStart(j)), len = length(xi - LOAD3(position, j));
    if (len0 < rest) start += 0.5 * springEnergyOf(params.collisionStiffness, rest - len0);
    if (len < rest) end += 0.5 * springEnergyOf(params.collisionStiffness, rest - len);
  }
}

// energyTerms: particle i's terms, in the order of ENERGY_TERMS.
void energyTerms(uint i, float dt, bool closed, out float terms[GB_ENERGY_TERMS]) {
  for (uint c = 0u; c < ENERGY_TERMS; ++c) terms[c] = 0.0;
  if (alive[i] == 0u) return;
  heldShares(i, terms[0], terms[2]);
  if (boundary[i] != 0u) return;  // prescribed: the wands' work
  const float m = mass[i];
  const vec3 vt = LOAD3(velocity, i);
  const vec3 moved = LOAD3(position, i) - LOAD3(previousPosition, i), v = moved / dt;
  terms[0] += 0.5 * m * dot(vt, vt);
  terms[1] = 0.5 * m * dot(v, v);
  terms[2] -= dot(LOAD3(force, i), moved);
  terms[3] = m;
  const vec3 momentum = m * v;
  terms[4] = momentum.x;
  terms[5] = momentum.y;
  terms[6] = momentum.z;
  const vec3 expected = closed ? m * vt + dt * LOAD3(force, i) : vec3(0.0);
  terms[7] = expected.x;
  terms[8] = expected.y;
  terms[9] = expected.z;
}

// boyleEnergyChange: the gas's energy change from volume `before` to `after`, as a difference.
float boyleEnergyChange(float referenceVolume, float before, float after) {
  if (!(before > 0.0 && after > 0.0 && referenceVolume > 0.0)) return 0.0;
  const float d = (after - before) / before;
  const float curvature =
      abs(d) < 0.1 ? d * d * (0.5 - d * (1.0 / 3.0 - d * (0.25 - d * (0.2 - d * (1.0 / 6.0 - d * (1.0 / 7.0))))))
                   : d - log(1.0 + d);
  return params.pressureCoefficient * ((before - referenceVolume) * d + referenceVolume * curvature);
}

// driftWithinBudget: the centre's velocity between `expected` and `centre` nearest `centre` within the speed.
vec3 driftWithinBudget(vec3 expected, vec3 centre, float speedSquared) {
  const vec3 made = centre - expected;
  const float a = dot(made, made), b = dot(expected, made), c = dot(expected, expected) - speedSquared;
  if (!(a > 0.0)) return centre;
  float l = clamp(-b / a, 0.0, 1.0);
  const float discriminant = b * b - a * c;
  if (discriminant >= 0.0) {
    const float root = sqrt(discriminant), lower = (-b - root) / a, upper = (-b + root) / a;
    if (upper >= 0.0 && lower <= 1.0) l = min(upper, 1.0);
  }
  return expected + l * made;
}

// energyScale: the factor on the motion about the centre of mass (scale), the centre's velocity, its shift and the
// energy the step released below its budget.
void energyScale(float start, float kinetic, float held, float mass, vec3 momentum, vec3 expectedMomentum,
                 out float scale, out vec3 centre, out vec3 shift, out float released) {
  scale = 1.0;
  centre = vec3(0.0);
  shift = vec3(0.0);
  released = 0.0;
  const float budget = start + float(GB_ENERGY_BUDGET_TOLERANCE) * abs(start);
  const float ended = kinetic + held;
  if (isinf(budget) || isnan(budget) || isinf(ended) || isnan(ended)) return;
  if (!(ended > budget) || !(mass > 0.0)) {
    released = max(0.0, start - ended);
    return;
  }
  const float drift = 0.5 * dot(momentum, momentum) / mass, internal = kinetic - drift;
  const float room = budget - held;
  centre = momentum / mass;
  if (room >= drift) {  // the wobble holds the excess
    scale = internal > 0.0 ? sqrt(clamp((room - drift) / internal, 0.0, 1.0)) : 1.0;
    return;
  }
  scale = 0.0;  // not even the drift was paid for: no wobble, and the drift given back as far as the film's own goes
  shift = driftWithinBudget(expectedMomentum / mass, centre, 2.0 * room / mass) - centre;
}

// budgetedVelocity: a free particle's new velocity as the budget leaves it.
vec3 budgetedVelocity(float scale, vec3 centre, vec3 shift, vec3 v) {
  return scale != 1.0 || shift != vec3(0.0) ? centre + shift + scale * (v - centre) : v;
}
