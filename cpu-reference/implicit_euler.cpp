#include "implicit_euler.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gb {

namespace {

constexpr float kTrustRegion = 0.25f;  // largest move per sweep, in shortest one-ring springs

// A particle's block while its terms are summed: the symmetric Hessian as its six distinct entries in locals,
// so that the sum stays in registers. (Summing 3x3 matrices built per term went through the stack, and the
// store-to-load stalls of those temporaries took half of the sweep's time: docs/performance.md, session 8.)
// Entry (r, c) gets scale (d_r d_c) per term, the same float operations as an outer-product matrix, so the sum
// equals the matrix sum bit for bit.
struct BlockSum {
  Vec3 gradient = Vec3::Zero();
  float xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  float shortestSpring = std::numeric_limits<float>::infinity();

  // hessian += scale d d^T
  void addOuter(float scale, const Vec3& d) {
    xx += scale * (d.x() * d.x());
    xy += scale * (d.x() * d.y());
    xz += scale * (d.x() * d.z());
    yy += scale * (d.y() * d.y());
    yz += scale * (d.y() * d.z());
    zz += scale * (d.z() * d.z());
  }
  // hessian += scale I
  void addIsotropic(float scale) {
    xx += scale;
    yy += scale;
    zz += scale;
  }
  [[nodiscard]] VertexBlock block() const {
    VertexBlock b;
    b.gradient = gradient;
    b.hessian << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    b.shortestSpring = shortestSpring;
    return b;
  }
};

// Damping along a direction, dissipation c/(2h) ((dx_i - dx_j) . dir)^2 with dx the displacement over the
// step: the implicit form of the damping force c ((v_j - v_i) . dir) dir. Its Hessian c/h dir dir^T is
// returned for the caller to add with the other terms along dir.
inline float addDampingGradient(float coefficient, float h, const Vec3& dir, const Vec3& relativeDisplacement,
                                BlockSum& b) {
  b.gradient += coefficient / h * relativeDisplacement.dot(dir) * dir;
  return coefficient / h;
}

// Physical model: tension x area of triangle (x, xj, xl), counter-clockwise. grad_x A = 1/2 n x (xl - xj);
// the Hessian of A in x alone is |xl - xj|^2 / (4 A) n n^T, positive semi-definite.
void addAreaTension(float tension, const Vec3& x, const Vec3& xj, const Vec3& xl, BlockSum& b) {
  const Vec3 twiceAreaNormal = (xj - x).cross(xl - x);
  const float twiceArea = twiceAreaNormal.norm();
  if (!(twiceArea > 0)) return;
  const Vec3 n = twiceAreaNormal / twiceArea;
  const Vec3 edge = xl - xj;
  b.gradient += tension * 0.5f * n.cross(edge);
  b.addOuter(tension * edge.squaredNorm() / (2.0f * twiceArea), n);
}

}  // namespace

float springStiffness(const State& s, size_t i, size_t j) { return 0.5f * (s.elasticity[i] + s.elasticity[j]); }

float transverseStiffness(float stiffness, float rest, float length) {
  return stiffness * std::max(0.0f, 1.0f - rest / length);
}

float triangleTension(const State& s, const uint32_t* corners) {
  return (s.elasticity[corners[0]] + s.elasticity[corners[1]] + s.elasticity[corners[2]]) / 3.0f;
}

namespace {

// The internal energies and dissipations of particle i at its current position x.
void addInternal(const Params& p, float h, const Topology& topo, const State& s, size_t i, BlockSum& b) {
  const Vec3 x = s.position.get(i), dx = x - s.previousPosition.get(i);
  const bool physical = p.tensionModel == 1;
  float isotropic = 0.0f;  // Hessian terms proportional to the identity, added once at the end
  for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
    const uint32_t j = topo.springNeighbour[k];
    const Vec3 xj = s.position.get(j);
    const Vec3 d = xj - x;
    const float len = d.norm();
    if (!(len > 0)) continue;
    const Vec3 dir = d / len;
    b.shortestSpring = std::min(b.shortestSpring, len);
    float along = addDampingGradient(p.springDamping, h, dir, dx - (xj - s.previousPosition.get(j)), b);
    if (!physical) {
      // The spring of Eq. (3), energy k/2 (len - l0)^2; Hessian k dir dir^T + k (1 - l0/len) (I - dir dir^T),
      // projected onto the positive semi-definite cone by dropping the transverse term of a compressed spring.
      const float stiffness = springStiffness(s, i, j);
      const float rest = topo.restLength[topo.springIndex[k]];
      b.gradient -= stiffness * (len - rest) * dir;
      const float transverse = transverseStiffness(stiffness, rest, len);
      isotropic += transverse;
      along += stiffness - transverse;
    }
    b.addOuter(along, dir);
  }
  b.addIsotropic(isotropic);
  if (physical) {
    for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k) {
      const uint32_t* tri = &topo.triangles[3 * topo.triangleIndex[k]];
      const uint32_t c = tri[0] == i ? 0u : (tri[1] == i ? 1u : 2u);
      addAreaTension(triangleTension(s, tri), x, s.position.get(tri[(c + 1) % 3]), s.position.get(tri[(c + 2) % 3]), b);
    }
  }
  // Contacts: penalty k_c/2 (d_c - |x - xj|)^2 inside the pair's rest distance d_c (its transverse Hessian term is
  // negative and dropped), damped while the two approach. The partner is taken where inertia carries it,
  // x_t + h v_t, not where the sweep has moved it: contacts then need no colouring of their own, the colouring
  // changes only with the mesh, and the sweep's result does not depend on which contacts were found.
  const uint32_t base = static_cast<uint32_t>(s.size()) + 1;
  for (uint32_t k = topo.contacts[i]; k < topo.contacts[i + 1]; ++k) {
    const uint32_t j = topo.contacts[base + k];
    const Vec3 xj = s.previousPosition.get(j) + h * s.velocity.get(j);
    const Vec3 d = x - xj;
    const float len = d.norm(), rest = contactRestDistance(topo.contacts, s.size(), k);
    if (!(len > 0 && len < rest)) continue;
    const Vec3 away = d / len;
    b.gradient -= p.collisionStiffness * (rest - len) * away;
    b.addOuter(p.collisionStiffness, away);
    const Vec3 relative = dx - (xj - s.previousPosition.get(j));
    if (relative.dot(away) < 0) b.addOuter(addDampingGradient(p.collisionDamping, h, away, relative, b), away);
  }
}

}  // namespace

Vec3 solveLinear3(const Eigen::Matrix3f& a, const Vec3& b) {
  const float c00 = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1), c01 = a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2),
              c02 = a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1);
  const float c10 = a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2), c11 = a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0),
              c12 = a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2);
  const float c20 = a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0), c21 = a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1),
              c22 = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
  const float det = a(0, 0) * c00 + a(0, 1) * c10 + a(0, 2) * c20;
  return Vec3(c00 * b.x() + c01 * b.y() + c02 * b.z(), c10 * b.x() + c11 * b.y() + c12 * b.z(),
              c20 * b.x() + c21 * b.y() + c22 * b.z()) /
         det;
}

float breathingStiffness(const Bubble& bubble, float area) {
  if (!(bubble.volume > 0)) return 0.0f;
  constexpr float sphereShape = 36.0f * 3.14159265f;  // A^3 = 36 pi V^2 for a sphere
  return bubble.pressure * area * std::cbrt(sphereShape / bubble.volume);
}

int solverSweeps(const Params& p, const StepUniforms& u) {
  return u.solverIterations > 0 ? u.solverIterations : p.solverIterations;
}

void predictImplicitStep(const StepUniforms& u, const Topology& topo, State& s, size_t i) {
  if (!s.alive[i]) return;
  const Vec3 x = s.position.get(i);
  s.previousPosition.set(i, x);
  if (topo.boundary[i]) {
    if (s.frameParam[i] >= 0.0f) s.position.set(i, framePoint(u.frameNext, s.frameParam[i]));
    return;
  }
  s.position.set(i, aboveFloor(x + u.dt * s.velocity.get(i)));
}

VertexBlock objectiveBlock(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo,
                           const State& s, size_t i) {
  const float h = u.dt, m = s.mass[i];
  const Vec3 x = s.position.get(i), xt = s.previousPosition.get(i);
  const Vec3 y = xt + h * s.velocity.get(i) + (h * h / m) * s.force.get(i);
  const float inertia = m / (h * h), drag = p.airDrag * s.voronoiArea[i] / h;
  BlockSum b;
  b.gradient = inertia * (x - y) + drag * (x - xt);
  b.addIsotropic(inertia + drag);
  addInternal(p, h, topo, s, i, b);
  const Vec3 n = s.normal.get(i);                                               // the normal of the step's start
  b.addOuter(addDampingGradient(airCoupling(p, u, s, i), h, n, x - xt, b), n);  // moving with the air
  if (u.closed) {  // Boyle's pressure at the iterate's volume, along the normal of the step's start
    b.gradient -= boyleForce(p, bubble.pressure, s, i);
    b.addOuter(breathingStiffness(bubble, s.voronoiArea[i]), n);
  }
  return b.block();
}

Vec3 trustedNewtonStep(const VertexBlock& b) {
  // The Hessian is at least (m / h^2) I, so it is invertible; a non-finite gradient gives a non-finite step,
  // which the caller leaves unapplied for the stability check to report.
  return withinTrustRegion(solveLinear3(b.hessian, b.gradient), b.shortestSpring);
}

Vec3 withinTrustRegion(Vec3 step, float shortestSpring) {
  // A sweep moves a particle at most kTrustRegion of its shortest spring. The area energy of the physical
  // model has no curvature in the film's plane (A is linear in a corner's height), so there the Newton step is
  // only held by the film's small inertia and would fold triangles over.
  const float limit = kTrustRegion * shortestSpring, length = step.norm();
  if (length > limit) step *= limit / length;
  return step;
}

Vec3 aboveFloor(Vec3 x) {
  x.y() = std::max(x.y(), 0.0f);
  return x;
}

void solveVertexBlock(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo, State& s,
                      size_t i) {
  if (!s.alive[i]) return;  // died in a burst since the colouring was made
  const Vec3 step = trustedNewtonStep(objectiveBlock(p, u, bubble, topo, s, i));
  if (!step.allFinite()) return;
  s.position.set(i, aboveFloor(s.position.get(i) - step));
}

double implicitResidual(const Params& p, const StepUniforms& u, const Bubble& bubble, const Topology& topo,
                        const State& s) {
  double sum = 0;
  for (uint32_t i : topo.colourOrder)
    sum += objectiveBlock(p, u, bubble, topo, s, i).gradient.cast<double>().squaredNorm();
  return std::sqrt(sum);
}

void finishImplicitStep(const StepUniforms& u, State& s, size_t i) {
  if (!s.alive[i]) return;
  s.velocity.set(i, (s.position.get(i) - s.previousPosition.get(i)) / u.dt);
}

}  // namespace gb
