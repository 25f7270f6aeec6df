#include "research/solver_comparison.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "solver/coarse_correction.h"
#include "solver/energy_budget.h"

namespace gb {

namespace {

// Runs body(i) for every solved particle in parallel: each writes only particle i.
template <class Body>
void forEachSolved(const std::vector<uint32_t>& solved, Body&& body) {
  const auto count = static_cast<long>(solved.size());
#pragma omp parallel for schedule(static)
  for (long k = 0; k < count; ++k) body(solved[static_cast<size_t>(k)]);
}

// Sum over the solved particles of term(i), in double.
template <class Term>
double sumSolved(const std::vector<uint32_t>& solved, Term&& term) {
  const auto count = static_cast<long>(solved.size());
  double sum = 0;
#pragma omp parallel for schedule(static) reduction(+ : sum)
  for (long k = 0; k < count; ++k) sum += term(solved[static_cast<size_t>(k)]);
  return sum;
}

double dot(const Vec3& a, const Vec3& b) { return static_cast<double>(a.dot(b)); }

void copyPositions(const Vec3Array& from, Vec3Array& to) {
  to.x = from.x;
  to.y = from.y;
  to.z = from.z;
}

// The particles the solver moves: the coloured ones still alive (a burst may have killed some since the colouring).
std::vector<uint32_t> solvedParticles(const Topology& topo, const State& s) {
  std::vector<uint32_t> solved;
  for (uint32_t i : topo.colourOrder)
    if (s.alive[i]) solved.push_back(i);
  return solved;
}

// Per particle: 1 where the solver moves it.
std::vector<char> solvedFlags(const std::vector<uint32_t>& solved, size_t n) {
  std::vector<char> flags(n, 0);
  for (uint32_t i : solved) flags[i] = 1;
  return flags;
}

// Particle i's own terms of the objective and its half of each spring it shares with another solved particle
// (the whole spring when the other end is fixed), in double.
double particleObjective(const Params& p, const StepUniforms& u, const Topology& topo, const State& s,
                         const std::vector<char>& solved, size_t i) {
  const double h = u.dt, m = s.mass[i];
  const Vec3 x = s.position.get(i), xt = s.previousPosition.get(i), dx = x - xt;
  const Vec3 y = xt + u.dt * s.velocity.get(i) + (u.dt * u.dt / s.mass[i]) * s.force.get(i);
  const Vec3 n = s.normal.get(i);
  double e = m / (2 * h * h) * (x - y).cast<double>().squaredNorm();
  e += p.airDrag * s.voronoiArea[i] / (2 * h) * dx.cast<double>().squaredNorm();
  e += airCoupling(p, u, s, i) / (2 * h) * std::pow(dot(n, dx), 2);
  for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
    const uint32_t j = topo.springNeighbour[k];
    const Vec3 xj = s.position.get(j), d = xj - x;
    const float len = d.norm();
    if (!(len > 0)) continue;
    const Vec3 dir = d / len, relative = dx - (xj - s.previousPosition.get(j));
    double spring = p.springDamping / (2 * h) * std::pow(dot(relative, dir), 2);
    if (p.tensionModel != 1) {
      const double stretch = static_cast<double>(len) - topo.restLength[topo.springIndex[k]];
      spring += springEnergyOf<double>(springStiffness(s, i, j), stretch);
    }
    e += (solved[j] ? 0.5 : 1.0) * spring;
  }
  const uint32_t base = static_cast<uint32_t>(s.size()) + 1;
  for (uint32_t k = topo.contacts[i]; k < topo.contacts[i + 1]; ++k) {
    const uint32_t j = topo.contacts[base + k];
    const Vec3 xj = s.previousPosition.get(j) + u.dt * s.velocity.get(j), d = x - xj;
    const float len = d.norm(), rest = contactRestDistance(topo.contacts, s.size(), k);
    if (!(len > 0 && len < rest)) continue;
    const Vec3 away = d / len;
    e += 0.5 * p.collisionStiffness * std::pow(rest - len, 2);
    const double approach = std::min(0.0, dot(dx - (xj - s.previousPosition.get(j)), away));
    e += p.collisionDamping / (2 * h) * approach * approach;
  }
  return e;
}

// Physical model: sum over the triangles with a solved corner of their tension energy (triangleTensionEnergy).
double areaObjective(const Params& p, const Topology& topo, const State& s, const std::vector<char>& solved) {
  double e = 0;
  for (size_t t = 0; t < topo.triangleCount(); ++t) {
    const uint32_t* tri = &topo.triangles[3 * t];
    if (!solved[tri[0]] && !solved[tri[1]] && !solved[tri[2]]) continue;
    const Vec3 x0 = s.position.get(tri[0]);
    const double area = 0.5 * (s.position.get(tri[1]) - x0).cross(s.position.get(tri[2]) - x0).cast<double>().norm();
    e += triangleTensionEnergy(p, triangleTension(s, tri), triangleAreaAtStart(topo, s, tri), area);
  }
  return e;
}

}  // namespace

std::string describe(const SolverChoice& c) {
  char buf[96];
  switch (c.kind) {
    case SolverKind::VertexBlockDescent:
      if (c.rho > 0)
        std::snprintf(buf, sizeof buf, "Chebyshev VBD, rho %.3f", c.rho);
      else
        std::snprintf(buf, sizeof buf, "VBD");
      break;
    case SolverKind::Jacobi:
      if (c.rho > 0)
        std::snprintf(buf, sizeof buf, "Chebyshev Jacobi, rho %.3f, relax %.2f", c.rho, c.relaxation);
      else
        std::snprintf(buf, sizeof buf, "Jacobi, relax %.2f", c.relaxation);
      break;
    case SolverKind::NewtonPcg:
      std::snprintf(buf, sizeof buf, "Newton-PCG, %d CG per Newton", c.cgPerNewton);
      break;
  }
  return buf;
}

double implicitObjective(const Params& p, const StepUniforms& u, const Topology& topo, const State& s) {
  if (u.closed) throw std::invalid_argument("implicitObjective: open films only (a bubble's gas needs its volume)");
  const std::vector<uint32_t> particles = solvedParticles(topo, s);
  const std::vector<char> solved = solvedFlags(particles, s.size());
  double e = sumSolved(particles, [&](size_t i) { return particleObjective(p, u, topo, s, solved, i); });
  if (p.tensionModel == 1) e += areaObjective(p, topo, s, solved);
  return e;
}

ImplicitSolve::ImplicitSolve(const Params& p, const StepUniforms& u, Film& film, SolverChoice choice)
    : params_(p), uniforms_(u), film_(film), choice_(choice), solved_(solvedParticles(film.topology, film.state)) {
  if (u.closed) throw std::invalid_argument("ImplicitSolve: open films only (a bubble's gas needs its volume)");
  if (!(choice.relaxation > 0 && choice.relaxation <= 1) || !(choice.rho >= 0 && choice.rho < 1) ||
      choice.cgPerNewton < 1)
    throw std::invalid_argument("ImplicitSolve: relaxation in (0, 1], rho in [0, 1), cgPerNewton >= 1");
  const size_t n = film.state.size();
  for (Vec3Array* a : {&older_, &step_, &start_, &delta_, &residual_, &direction_, &preconditioned_, &product_})
    a->resize(n);
  if (choice.kind == SolverKind::NewtonPcg) blocks_.resize(n);
}

void ImplicitSolve::iterate() {
  ++iterations_;
  if (choice_.kind == SolverKind::NewtonPcg) {
    if ((iterations_ - 1) % choice_.cgPerNewton == 0) startNewton();
    conjugateGradientIteration();
    return;
  }
  Vec3Array beforeSweep;
  if (choice_.rho > 0) copyPositions(film_.state.position, beforeSweep);
  if (choice_.kind == SolverKind::VertexBlockDescent)
    vbdSweep();
  else
    jacobiPass();
  if (choice_.rho > 0) chebyshev(beforeSweep);
}

void ImplicitSolve::vbdSweep() {
  const Topology& topo = film_.topology;
  for (size_t c = 0; c + 1 < topo.colourOffset.size(); ++c) {
    const uint32_t first = topo.colourOffset[c];
    const auto count = static_cast<long>(topo.colourOffset[c + 1] - first);
#pragma omp parallel for schedule(static)
    for (long k = 0; k < count; ++k)
      vertexBlockDescent(params_, uniforms_, Bubble{}, topo, film_.state,
                         topo.colourOrder[first + static_cast<size_t>(k)]);
  }
}

void ImplicitSolve::jacobiPass() {
  State& s = film_.state;
  forEachSolved(solved_, [&](size_t i) {
    const Vec3 step = trustedNewtonStep(objectiveBlock(params_, uniforms_, Bubble{}, film_.topology, s, i));
    step_.set(i, step.allFinite() ? Vec3(choice_.relaxation * step) : Vec3::Zero());
  });
  forEachSolved(solved_, [&](size_t i) { s.position.set(i, aboveFloor(s.position.get(i) - step_.get(i))); });
}

void ImplicitSolve::chebyshev(const Vec3Array& beforeSweep) {
  const float rho2 = choice_.rho * choice_.rho;
  omega_ = iterations_ == 1 ? 1.0f : (iterations_ == 2 ? 2.0f / (2.0f - rho2) : 4.0f / (4.0f - rho2 * omega_));
  if (iterations_ >= 2) {
    Vec3Array& x = film_.state.position;
    forEachSolved(solved_, [&](size_t i) {
      const Vec3 older = older_.get(i);
      x.set(i, aboveFloor(omega_ * (x.get(i) - older) + older));
    });
  }
  copyPositions(beforeSweep, older_);  // x_{k-1} is x_{k-2} of the next iteration
}

void ImplicitSolve::startNewton() {
  const State& s = film_.state;
  copyPositions(s.position, start_);
  residualDot_ = sumSolved(solved_, [&](size_t i) {
    blocks_[i] = objectiveBlock(params_, uniforms_, Bubble{}, film_.topology, s, i);
    const Vec3 r = -blocks_[i].gradient, z = solveLinear3(blocks_[i].hessian, r);
    residual_.set(i, r);
    preconditioned_.set(i, z);
    direction_.set(i, z);
    delta_.set(i, Vec3::Zero());
    return dot(r, z);
  });
}

void ImplicitSolve::conjugateGradientIteration() {
  hessianProduct(direction_, product_);
  const double curvature = sumSolved(solved_, [&](size_t i) { return dot(direction_.get(i), product_.get(i)); });
  if (!(curvature > 0) || !(residualDot_ > 0)) return;  // converged to float precision, or broken down
  const auto alpha = static_cast<float>(residualDot_ / curvature);
  const double next = sumSolved(solved_, [&](size_t i) {
    delta_.set(i, delta_.get(i) + alpha * direction_.get(i));
    const Vec3 r = residual_.get(i) - alpha * product_.get(i), z = solveLinear3(blocks_[i].hessian, r);
    residual_.set(i, r);
    preconditioned_.set(i, z);
    return dot(r, z);
  });
  const auto beta = static_cast<float>(next / residualDot_);
  residualDot_ = next;
  State& s = film_.state;
  forEachSolved(solved_, [&](size_t i) {
    direction_.set(i, preconditioned_.get(i) + beta * direction_.get(i));
    s.position.set(i, aboveFloor(start_.get(i) + withinTrustRegion(delta_.get(i), blocks_[i].shortestSpring)));
  });
}

void ImplicitSolve::hessianProduct(const Vec3Array& v, Vec3Array& out) const {
  const State& s = film_.state;
  const Topology& topo = film_.topology;
  const float h = uniforms_.dt;
  forEachSolved(solved_, [&](size_t i) {
    // The diagonal block (inertia, drag, air coupling, contacts, and the one-ring's own terms), then the
    // off-diagonal blocks of the springs and triangles (coarse_correction.h); v is zero on the particles that are
    // not solved.
    Vec3 sum = blocks_[i].hessian * v.get(i);
    for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k)
      sum += springCouplingBlock(params_, h, topo, s, start_, i, k) * v.get(topo.springNeighbour[k]);
    if (params_.tensionModel == 1) {
      for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k) {
        const uint32_t corner = topo.triangleCorner[k], c = corner % 3;
        const uint32_t* tri = topo.triangleOf(corner);
        for (uint32_t l = 0; l < 3; ++l)
          if (l != c) sum += triangleCouplingBlock(params_, topo, s, start_, tri, c, l) * v.get(tri[l]);
      }
    }
    out.set(i, sum);
  });
}

}  // namespace gb
