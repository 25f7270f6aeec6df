// The implicit step's per-particle block (objectiveBlock of cpu-reference/solver/implicit_euler.cpp): the gradient and
// Hessian of the step's objective in x_i with every other particle fixed. Included by the kernels that solve
// (vertex_block_descent) or gather (coarse_assemble) the blocks; each function has its C++ twin's name.

// The gradient and Hessian of the objective in x_i, summed term by term (Block of the C++ twin).
vec3 gradient;
mat3 hessian;
float shortestSpring;  // of the particle's one-ring (m)

// addDampingGradient: dissipation c/(2h) ((dx_i - dx_j) . dir)^2; returns its Hessian's factor along dir.
float addDampingGradient(float coefficient, float h, vec3 dir, vec3 relativeDisplacement) {
  gradient += coefficient / h * dot(relativeDisplacement, dir) * dir;
  return coefficient / h;
}

// addAreaTension: the tension energy of triangle (x, xj, xl), counter-clockwise, from its start's tension and area.
void addAreaTension(float startTension, float startArea, vec3 x, vec3 xj, vec3 xl) {
  const vec3 twiceAreaNormal = cross(xj - x, xl - x);
  const float twiceArea = length(twiceAreaNormal);
  if (!(twiceArea > 0.0)) return;
  const vec3 n = twiceAreaNormal / twiceArea;
  const vec3 edge = xl - xj;
  const TriangleTension t = triangleTensionOf(startTension, startArea, 0.5 * twiceArea);
  const vec3 areaGradient = 0.5 * cross(n, edge);
  gradient += t.tension * areaGradient;
  hessian += t.tension * dot(edge, edge) / (2.0 * twiceArea) * outerProduct(n, n);
  hessian += t.slope * outerProduct(areaGradient, areaGradient);
}

// addInternal: the internal energies and dissipations of particle i at its current position.
void addInternal(float h, uint i) {
  const vec3 x = LOAD3(position, i), dx = x - LOAD3(previousPosition, i);
  const bool physical = params.tensionModel == 1;
  float isotropic = 0.0;
  for (uint k = springOffset[i]; k < springOffset[i + 1u]; ++k) {
    const uint j = springNeighbour[k];
    const vec3 xj = LOAD3(position, j);
    const vec3 d = xj - x;
    const float len = length(d);
    if (!(len > 0.0)) continue;
    const vec3 dir = d / len;
    shortestSpring = min(shortestSpring, len);
    float along = addDampingGradient(params.springDamping, h, dir, dx - (xj - LOAD3(previousPosition, j)));
    if (!physical) {  // the spring of Eq. (3), its Hessian projected as in the C++ twin
      const float stiffness = 0.5 * (elasticity[i] + elasticity[j]);
      const float rest = restLength[springIndex[k]];
      gradient -= stiffness * (len - rest) * dir;
      const float transverse = stiffness * max(0.0, 1.0 - rest / len);
      isotropic += transverse;
      along += stiffness - transverse;
    }
    hessian += along * outerProduct(dir, dir);
  }
  hessian += isotropic * mat3(1.0);
  if (physical) {
    for (uint k = triangleOffset[i]; k < triangleOffset[i + 1u]; ++k) {
      const uint corner = triangleCorner[k], t = corner / 3u, c = corner % 3u;
      const float tension =
          (elasticity[triangles[3u * t]] + elasticity[triangles[3u * t + 1u]] + elasticity[triangles[3u * t + 2u]]) /
          3.0;
      addAreaTension(tension, triangleAreaAtStart(t), x, LOAD3(position, triangles[3u * t + (c + 1u) % 3u]),
                     LOAD3(position, triangles[3u * t + (c + 2u) % 3u]));
    }
  }
  const uint base = pc.particles + 1u;
  for (uint k = contacts[i]; k < contacts[i + 1u]; ++k) {  // the partner where inertia carries it (C++ twin)
    const uint j = contacts[base + k];
    const vec3 xj = LOAD3(previousPosition, j) + h * LOAD3(velocity, j);
    const vec3 d = x - xj;
    const float len = length(d), rest = contactRestDistance(k);
    if (!(len > 0.0 && len < rest)) continue;
    const vec3 away = d / len;
    gradient -= params.collisionStiffness * (rest - len) * away;
    hessian += params.collisionStiffness * outerProduct(away, away);
    const vec3 relative = dx - (xj - LOAD3(previousPosition, j));
    if (dot(relative, away) < 0.0)
      hessian += addDampingGradient(params.collisionDamping, h, away, relative) * outerProduct(away, away);
  }
}

// breathingStiffness: P A A_total / V with A_total as for a sphere.
float breathingStiffness(float volume, float pressure, float area) {
  if (!(volume > 0.0)) return 0.0;
  const float sphereShape = 36.0 * 3.14159265;
  return pressure * area * pow(sphereShape / volume, 1.0 / 3.0);
}

// solveLinear3: a x = b by the adjugate; a(r, c) is a[c][r] (GLSL matrices are column-major).
vec3 solveLinear3(mat3 a, vec3 b) {
  const float c00 = a[1][1] * a[2][2] - a[2][1] * a[1][2], c01 = a[2][0] * a[1][2] - a[1][0] * a[2][2],
              c02 = a[1][0] * a[2][1] - a[2][0] * a[1][1];
  const float c10 = a[2][1] * a[0][2] - a[0][1] * a[2][2], c11 = a[0][0] * a[2][2] - a[2][0] * a[0][2],
              c12 = a[2][0] * a[0][1] - a[0][0] * a[2][1];
  const float c20 = a[0][1] * a[1][2] - a[1][1] * a[0][2], c21 = a[1][0] * a[0][2] - a[0][0] * a[1][2],
              c22 = a[0][0] * a[1][1] - a[1][0] * a[0][1];
  const float det = a[0][0] * c00 + a[1][0] * c10 + a[2][0] * c20;
  return vec3(c00 * b.x + c01 * b.y + c02 * b.z, c10 * b.x + c11 * b.y + c12 * b.z, c20 * b.x + c21 * b.y + c22 * b.z) /
         det;
}

// objectiveBlock: the whole block of particle i at the current positions, into gradient, hessian and
// shortestSpring.
void objectiveBlock(StepUniformsBlock u, uint i) {
  const float h = u.dt, m = mass[i];
  const vec3 x = LOAD3(position, i), xt = LOAD3(previousPosition, i);
  const vec3 y = xt + h * LOAD3(velocity, i) + (h * h / m) * LOAD3(force, i);
  const float inertia = m / (h * h), drag = params.airDrag * voronoiArea[i] / h;
  gradient = inertia * (x - y) + drag * (x - xt);
  hessian = (inertia + drag) * mat3(1.0);
  shortestSpring = 1.0 / 0.0;  // +infinity, as the C++ twin's
  addInternal(h, i);
  const vec3 n = LOAD3(normal, i);  // the normal of the step's start
  hessian += addDampingGradient(airCoupling(u, i), h, n, x - xt) * outerProduct(n, n);  // moving with the air
  if (u.closed != 0u) {  // Boyle's pressure at the iterate's volume
    const float pressure = currentPressure(u);
    gradient -= boyleForce(pressure, i);
    hessian += breathingStiffness(currentVolume(), pressure, voronoiArea[i]) * outerProduct(n, n);
  }
}

// withinTrustRegion: a move shortened to kTrustRegion of the shortest spring (the C++ twin says why).
vec3 withinTrustRegion(vec3 step, float shortest) {
  const float limit = kTrustRegion * shortest, len = length(step);
  return len > limit ? step * (limit / len) : step;
}
