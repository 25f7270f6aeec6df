#include "stages/stages.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "model/film.h"
#include "solver/energy_budget.h"
#include "solver/particle_lanes.h"

namespace gb {

WandState wandsOf(const StepUniforms& u) {
  return {toVec3(u.leftPosition), toVec3(u.leftVelocity), toVec3(u.rightPosition), toVec3(u.rightVelocity)};
}

void setWands(StepUniforms& u, const WandState& wands) {
  u.leftPosition = toVec4(wands.leftPosition);
  u.leftVelocity = toVec4(wands.leftVelocity);
  u.rightPosition = toVec4(wands.rightPosition);
  u.rightVelocity = toVec4(wands.rightVelocity);
}

WireFrame wireNextOf(const StepUniforms& u) {
  WireFrame f;
  f.kind = static_cast<ToolKind>(u.wireKind);
  f.center = toVec3(u.wireCenter);
  f.axis = toVec3(u.wireAxis);
  f.down = toVec3(u.wireDown);
  f.halfWidth = u.wireHalfWidth;
  f.depth = u.wireDepth;
  return f;
}

void setWireNext(StepUniforms& u, const WireFrame& frame) {
  u.wireKind = static_cast<int>(frame.kind);
  u.wireCenter = toVec4(frame.center);
  u.wireAxis = toVec4(frame.axis);
  u.wireDown = toVec4(frame.down);
  u.wireHalfWidth = frame.halfWidth;
  u.wireDepth = frame.depth;
}

// ---- geometry ---------------------------------------------------------------------------------------------

namespace {

// Mixed Voronoi area of corner xi of triangle (xi, xj, xk) whose area is `area` (Meyer et al. 2003,
// Fig. 4): the Voronoi region for a non-obtuse triangle, else half or a quarter of the triangle so that the
// areas still tile it. The cotangents of Meyer's formula share the denominator |cross| = 2 area, so
// A_i = (|e_ij|^2 cot k + |e_ik|^2 cot j) / 8 = (|e_ij|^2 dot_k + |e_ik|^2 dot_j) / (16 area).
// Written once for one float and for four lanes (float_lanes.h: the same floats in each lane): every case is
// computed and the one that applies selected.
template <class F>
F mixedVoronoiCorner(const Vec3Of<F>& xi, const Vec3Of<F>& xj, const Vec3Of<F>& xk, F area) {
  const Vec3Of<F> eij = xj - xi, eik = xk - xi, ejk = xk - xj;
  const F ij2 = dot(eij, eij), ik2 = dot(eik, eik);
  const F dotI = dot(eij, eik), dotJ = F(-1.0f) * dot(eij, ejk), dotK = dot(eik, ejk);  // cosines times lengths
  const F zero(0.0f);
  F corner = select(dotJ < zero || dotK < zero, F(0.25f) * area, (ij2 * dotK + ik2 * dotJ) / (F(16.0f) * area));
  corner = select(dotI < zero, F(0.5f) * area, corner);
  // A collapsed triangle (area below 1e-6 of its edges' squares, e.g. torn film folding at a hole's rim)
  // has no meaningful angles: its corners share its vanishing area equally instead of dividing by it.
  return select(area > F(1e-6f) * (ij2 + ik2), corner, area / F(3.0f));
}

// A triangle's (x1 - x0) x (x2 - x0) and its corners' mixed Voronoi areas.
template <class F>
void triangleGeometryOf(const std::array<Vec3Of<F>, 3>& x, Vec3Of<F>& doubleAreaNormal, std::array<F, 3>& corners) {
  doubleAreaNormal = cross(x[1] - x[0], x[2] - x[0]);
  const F area = F(0.5f) * norm(doubleAreaNormal);
  for (size_t c = 0; c < 3; ++c) corners[c] = mixedVoronoiCorner(x[c], x[(c + 1) % 3], x[(c + 2) % 3], area);
}

}  // namespace

void triangleGeometry(const Topology& topo, State& s, size_t t) {
  const uint32_t* tri = &topo.triangles[3 * t];
  Vec3Of<float> normal{};
  std::array<float, 3> corners{};
  triangleGeometryOf<float>(
      {lanesOf(s.position.get(tri[0])), lanesOf(s.position.get(tri[1])), lanesOf(s.position.get(tri[2]))}, normal,
      corners);
  s.triangleNormal.set(t, Vec3(normal.x, normal.y, normal.z));
  for (size_t c = 0; c < 3; ++c) s.cornerArea[3 * t + c] = corners[c];
}

void triangleGeometries(const Topology& topo, State& s, size_t first, size_t last) {
  size_t t = first;
  for (; t + 4 <= last; t += 4) {
    std::array<Vec3Of<Float4>, 3> x;
    for (size_t c = 0; c < 3; ++c) {
      const std::array<uint32_t, 4> corner{topo.triangles[3 * t + c], topo.triangles[3 * (t + 1) + c],
                                           topo.triangles[3 * (t + 2) + c], topo.triangles[3 * (t + 3) + c]};
      x[c] = gatherVec<Float4>(s.position, corner);
    }
    Vec3Of<Float4> normal;
    std::array<Float4, 3> corners;
    triangleGeometryOf(x, normal, corners);
    normal.x.store(&s.triangleNormal.x[t]);
    normal.y.store(&s.triangleNormal.y[t]);
    normal.z.store(&s.triangleNormal.z[t]);
    for (int l = 0; l < 4; ++l)
      for (size_t c = 0; c < 3; ++c) s.cornerArea[3 * (t + static_cast<size_t>(l)) + c] = corners[c].lane(l);
  }
  for (; t < last; ++t) triangleGeometry(topo, s, t);
}

void vertexGeometry(const Topology& topo, State& s, size_t i) {
  Vec3 normalSum = Vec3::Zero();
  float area = 0.0f;
  for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k) {
    const uint32_t corner = topo.triangleCorner[k];
    normalSum += s.triangleNormal.get(corner / 3);
    area += s.cornerArea[corner];
  }
  const float len = normalSum.norm();
  s.normal.set(i, len > 0 ? Vec3(normalSum / len) : Vec3::Zero());
  s.voronoiArea[i] = area;
}

void fitTriangleArrays(const Topology& topo, State& s) {
  if (s.cornerArea.size() == 3 * topo.triangleCount() && s.triangleNormal.size() == topo.triangleCount()) return;
  s.triangleNormal.resize(topo.triangleCount());
  s.cornerArea.assign(3 * topo.triangleCount(), 0.0f);
}

uint64_t geometryKey(const Topology& topo, const State& s) {
  // Word by word, multiply and rotate, in four independent lanes (word k into lane k % 4) so that the
  // multiplications overlap instead of waiting for each other: about a millisecond for 1,000,000 particles, against
  // the geometry's 30-50. Not cryptographic, but a changed position or triangle changes the key but for a 2^-64
  // chance.
  std::array<uint64_t, 4> lane{0x9E3779B97F4A7C15ull ^ (static_cast<uint64_t>(s.size()) << 32) ^ topo.triangles.size(),
                               1, 2, 3};
  const auto mix = [](uint64_t& h, uint64_t word) { h = std::rotl((h ^ word) * 0xFF51AFD7ED558CCDull, 29); };
  const auto mixWords = [&](const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    size_t k = 0;
    for (; k + 32 <= bytes; k += 32) {
      std::array<uint64_t, 4> words;
      std::memcpy(words.data(), p + k, 32);
      for (int l = 0; l < 4; ++l) mix(lane[l], words[l]);
    }
    for (; k + 8 <= bytes; k += 8) {
      uint64_t word;
      std::memcpy(&word, p + k, 8);
      mix(lane[0], word);
    }
    uint64_t tail = 0;
    if (k < bytes) std::memcpy(&tail, p + k, bytes - k);  // an empty array's data() may be null, even for 0 bytes
    mix(lane[0], tail);
  };
  for (const std::vector<float>* axis : {&s.position.x, &s.position.y, &s.position.z})
    mixWords(axis->data(), axis->size() * sizeof(float));
  mixWords(topo.triangles.data(), topo.triangles.size() * sizeof(uint32_t));
  for (int l = 1; l < 4; ++l) mix(lane[0], lane[l]);
  return lane[0];
}

void computeGeometry(const Topology& topo, State& s) {
  fitTriangleArrays(topo, s);
  for (size_t t = 0; t < topo.triangleCount(); ++t) triangleGeometry(topo, s, t);
  for (size_t i = 0; i < s.size(); ++i) vertexGeometry(topo, s, i);
}

void computeGeometryAround(const Topology& topo, State& s, std::span<const uint32_t> particles) {
  for (std::vector<float>* axis : {&s.triangleNormal.x, &s.triangleNormal.y, &s.triangleNormal.z})
    axis->resize(topo.triangleCount(), 0.0f);  // keeping the other triangles' (Vec3Array::resize clears)
  s.cornerArea.resize(3 * topo.triangleCount(), 0.0f);
  for (uint32_t i : particles)  // a triangle with several of them is computed again, to the same values
    for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k)
      triangleGeometry(topo, s, topo.triangleCorner[k] / 3);
  for (uint32_t i : particles) vertexGeometry(topo, s, i);
}

namespace {

template <class F>
F coneVolumeOf(const Vec3Of<F>& a, const Vec3Of<F>& b, const Vec3Of<F>& c, const Vec3Of<F>& origin) {
  return dot(a - origin, cross(b - origin, c - origin)) / F(6.0f);
}

}  // namespace

float coneVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& origin) {
  return coneVolumeOf(lanesOf(a), lanesOf(b), lanesOf(c), lanesOf(origin));
}

void triangleVolumes(const Topology& topo, const State& s, const Vec3& origin, bool atStepStart, size_t first,
                     size_t last, float* volumes) {
  const Vec3Of<Float4> apex = lanesOf(origin, origin, origin, origin);
  size_t t = first;
  for (; t + 4 <= last; t += 4) {
    std::array<Vec3Of<Float4>, 3> x;
    for (size_t c = 0; c < 3; ++c) {
      const std::array<uint32_t, 4> corner{topo.triangles[3 * t + c], topo.triangles[3 * (t + 1) + c],
                                           topo.triangles[3 * (t + 2) + c], topo.triangles[3 * (t + 3) + c]};
      // The sweeps' volumes read the current positions: gathered straight into the lanes.
      x[c] = atStepStart ? lanesOf(positionAtStepStart(topo, s, corner[0]), positionAtStepStart(topo, s, corner[1]),
                                   positionAtStepStart(topo, s, corner[2]), positionAtStepStart(topo, s, corner[3]))
                         : gatherVec<Float4>(s.position, corner);
    }
    coneVolumeOf(x[0], x[1], x[2], apex).store(volumes + t);
  }
  for (; t < last; ++t)
    volumes[t] = atStepStart ? triangleVolumeAtStart(topo, s, t, origin) : triangleVolume(topo, s, t, origin);
}

float triangleVolume(const Topology& topo, const State& s, size_t t, const Vec3& origin) {
  const uint32_t* tri = &topo.triangles[3 * t];
  return coneVolume(s.position.get(tri[0]), s.position.get(tri[1]), s.position.get(tri[2]), origin);
}

float treeSum(std::vector<float> v) { return treeSumInPlace(v); }

float treeSumInPlace(std::span<float> v) {
  if (v.empty()) return 0.0f;
  size_t n = v.size();
  while (n > 1) {
    const size_t pairs = n / 2;  // the pairs' sums, then an odd count's last element as it is
    size_t k = 0;
    // Four sums from eight elements at a time, loaded before the sums overwrite the first four of them: the
    // elements a later four reads, from 2 k on, lie past those an earlier one wrote.
    for (; k + 4 <= pairs; k += 4) pairSums(Float4::load(&v[2 * k]), Float4::load(&v[2 * k + 4])).store(&v[k]);
    for (; k < pairs; ++k) v[k] = v[2 * k] + v[2 * k + 1];
    if (n % 2 == 1) v[pairs] = v[n - 1];
    n = pairs + n % 2;
  }
  return v[0];
}

// ---- film state ------------------------------------------------------------------------------------------

float elasticityOf(const Params& p, float thickness, float lifetime) {
  const float x = thickness / p.elasticityThickness;                                      // e_i / k
  if (lifetime < p.marangoniLifetime) return p.elasticityWeight * 2.0f * x / (x + 2.0f);  // Marangoni
  const float g = std::max(x, p.gibbsFloorThickness / p.elasticityThickness);             // held below the floor
  return p.elasticityWeight * 4.0f * g / ((g + 2.0f) * (g + 2.0f));                       // Gibbs
}

float filmTension(const Params& p, float thickness) {
  const float gamma0 = p.surfaceTension;
  const float gamma = gamma0 + 0.5f * p.gibbsElasticity * std::log(initialThickness(p) / std::max(thickness, 1e-12f));
  return 2.0f * std::clamp(gamma, kLowestGammaFactor * gamma0, kHighestGammaFactor * gamma0);
}

double filmTensionEnergy(const Params& p, double liquid, double area) {
  const double a = area, e0 = initialThickness(p), gamma0 = p.surfaceTension, gibbs = p.gibbsElasticity;
  const double tension = filmTension(p, a > 0 ? static_cast<float>(liquid / a) : 0.0f);
  if (!(gibbs > 0)) return tension * a;
  // gamma = gamma_0 + (E_G / 2) ln(a e_0 / liquid) reaches gamma_0 / 2 at a_lo and 2 gamma_0 at a_hi. The constant
  // of integration makes W = 2 gamma a below a_lo (a thick film, gamma at its floor).
  const double lower = liquid / e0 * std::exp(2.0 * (kLowestGammaFactor - 1.0) * gamma0 / gibbs);
  const double upper = liquid / e0 * std::exp(2.0 * (kHighestGammaFactor - 1.0) * gamma0 / gibbs);
  return tension * a - gibbs * (std::clamp(a, lower, upper) - lower);
}

void filmState(const Params& p, float dt, State& s, size_t i) {
  const float area = s.voronoiArea[i];
  s.thickness[i] = area > 0 ? s.liquid[i] / area : 0.0f;
  s.elasticity[i] = p.tensionModel == 1 ? filmTension(p, area > 0 ? surfactantLiquid(p, s.mass[i]) / area : 0.0f)
                                        : elasticityOf(p, s.thickness[i], s.lifetime[i]);
  s.lifetime[i] += dt;
}

// ---- air ------------------------------------------------------------------------------------------------

Vec3 airInflowAt(const Params& p, const StepUniforms& u, const Vec3& x) {
  const WandState wands = wandsOf(u);
  const float dLeft = (x - wands.leftPosition).norm(), dRight = (x - wands.rightPosition).norm();
  const Vec3 sources = u.leftInflowWeight * wands.leftVelocity / (dLeft + p.airInflowDistance) +
                       wands.rightVelocity / (dRight + p.airInflowDistance);
  return -u.airVolume * u.wandAlignment * sources;
}

void airInflow(const Params& p, const StepUniforms& u, State& s, size_t i) {
  s.airInflow.set(i, airInflowAt(p, u, s.position.get(i)));
}

void airTransfer(const Params& p, const Topology& topo, State& s, size_t i) {
  if (topo.boundary[i] || p.airTransfer == 0) {  // Algorithm 2, line 2: the end particles take the new inflow
    s.airFlowNext.set(i, s.airInflow.get(i));
    return;
  }
  const Vec3 xi = s.position.get(i);
  Vec3 weighted = Vec3::Zero();
  float weightSum = 0.0f;
  for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
    const uint32_t j = topo.springNeighbour[k];
    const Vec3 airJ = s.airFlow.get(j);
    if (airJ == Vec3::Zero()) continue;  // sends nothing (a free bubble's air everywhere): no square roots spent
    const Vec3 toI = xi - s.position.get(j);
    const float norms = toI.norm() * airJ.norm();
    if (norms <= 0) continue;
    const float aDir = std::max(toI.dot(airJ) / norms, 0.0f);  // Eq. (7), seen from the sender j
    if (aDir <= p.airDirectionThreshold) continue;
    weighted += aDir * airJ;
    weightSum += aDir;
  }
  s.airFlowNext.set(i, weightSum > 0 ? Vec3(weighted / weightSum) : Vec3::Zero());  // Eq. (8)
}

// ---- forces ---------------------------------------------------------------------------------------------

float boylePressure(const Params& p, float referenceVolume, float currentVolume) {
  return currentVolume > 0 ? p.pressureCoefficient * referenceVolume / currentVolume : p.pressureCoefficient;
}

double boyleGasEnergy(const Params& p, double referenceVolume, double currentVolume) {
  if (!(referenceVolume > 0 && currentVolume > 0)) return 0.0;
  return p.pressureCoefficient *
         (referenceVolume * std::log(referenceVolume / currentVolume) + (currentVolume - referenceVolume));
}

Vec3 areaTensionForce(const Topology& topo, const State& s, size_t i) {
  Vec3 f = Vec3::Zero();
  for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k) {
    const uint32_t corner = topo.triangleCorner[k], t = corner / 3, c = corner % 3;
    const uint32_t* tri = &topo.triangles[3 * t];
    const uint32_t j = tri[(c + 1) % 3], l = tri[(c + 2) % 3];
    const Vec3 twiceAreaNormal = s.triangleNormal.get(t);
    const float twiceArea = twiceAreaNormal.norm();
    if (twiceArea <= 0) continue;
    const float tension = (s.elasticity[tri[0]] + s.elasticity[tri[1]] + s.elasticity[tri[2]]) / 3.0f;
    // grad_i A_t = 1/2 n_t x (x_l - x_j): the film pulls i towards the opposite edge, in the triangle's plane.
    f -= tension * 0.5f * (twiceAreaNormal / twiceArea).cross(s.position.get(l) - s.position.get(j));
  }
  return f;
}

Vec3 internalForce(const Params& p, const Topology& topo, const State& s, size_t i) {
  const Vec3 xi = s.position.get(i), vi = s.velocity.get(i);
  const float ei = s.elasticity[i];
  const bool physical = p.tensionModel == 1;
  Vec3 f = physical ? areaTensionForce(topo, s, i) : Vec3::Zero();
  for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
    const uint32_t j = topo.springNeighbour[k];
    const Vec3 d = s.position.get(j) - xi;
    const float len = d.norm();
    if (len <= 0) continue;
    const Vec3 dir = d / len;
    const float stiffness = 0.5f * (ei + s.elasticity[j]);
    if (!physical) f += stiffness * (len - topo.restLength[topo.springIndex[k]]) * dir;  // Eq. (3)
    f += p.springDamping * (s.velocity.get(j) - vi).dot(dir) * dir;                      // Algorithm 1, line 5
  }
  // Self-collision: contacts closer than their rest distance (collision.h) repel along their separation and damp their
  // approach; the tangential motion is free, so colliding sheets slip (Section 8).
  const uint32_t base = static_cast<uint32_t>(s.size()) + 1;
  for (uint32_t k = topo.contacts[i]; k < topo.contacts[i + 1]; ++k) {
    const uint32_t j = topo.contacts[base + k];
    const Vec3 d = xi - s.position.get(j);
    const float len = d.norm(), rest = contactRestDistance(topo.contacts, s.size(), k);
    if (!(len > 0 && len < rest)) continue;
    const Vec3 away = d / len;
    const float approach = (vi - s.velocity.get(j)).dot(away);
    f += p.collisionStiffness * (rest - len) * away;
    if (approach < 0) f -= p.collisionDamping * approach * away;
  }
  return f;
}

Vec3 externalForce(const Params& p, const StepUniforms& u, float pressure, const State& s, size_t i) {
  const Vec3 n = s.normal.get(i);
  const float area = s.voronoiArea[i];
  const float lifted = u.closed ? p.bubbleLift : 0.0f;  // a free bubble's air may carry some of its weight
  Vec3 f = (1.0f - lifted) * liquidMass(p, s.liquid[i]) * Vec3(p.gravityX, p.gravityY, p.gravityZ);
  const float flowIn = s.airFlow.get(i).dot(n), directIn = s.airInflow.get(i).dot(n);
  if (u.closed) {
    f += pressure / p.pressureCoefficient * p.airPressureGain * flowIn * area * n;  // Eq. (10), the air's part
  } else {
    f += p.airPressureGain * (flowIn + directIn) * area * n;  // Eq. (9)
  }
  return f;
}

float fullAirCoupling(const Params& p, float wireArea, float voronoiArea) {
  return p.airPressureGain * wireArea * voronoiArea;
}

float airCoupling(const Params& p, const StepUniforms& u, const State& s, size_t i) {
  if (u.closed || !(u.wireArea > 0)) return 0.0f;
  const float airSpeed = std::abs((s.airFlow.get(i) + s.airInflow.get(i)).dot(s.normal.get(i))) / u.wireArea;
  return fullAirCoupling(p, u.wireArea, s.voronoiArea[i]) * std::min(1.0f, airSpeed / kStillAirSpeed);
}

Vec3 volumeGradient(const Topology& topo, const State& s, size_t i) {
  Vec3 twiceAreaNormals = Vec3::Zero();
  for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k)
    twiceAreaNormals += s.triangleNormal.get(topo.triangleCorner[k] / 3);
  return twiceAreaNormals / 6.0f;
}

float boyleExcess(const Params& p, float pressure) { return pressure - p.pressureCoefficient; }

Vec3 boyleForce(const Params& p, float pressure, const Topology& topo, const State& s, size_t i) {
  return boyleExcess(p, pressure) * volumeGradient(topo, s, i);
}

void forces(const Params& p, const StepUniforms& u, float pressure, const Topology& topo, State& s, size_t i) {
  const Vec3 drag = -p.airDrag * s.voronoiArea[i] * s.velocity.get(i);  // still air resists
  const Vec3 n = s.normal.get(i);
  const Vec3 coupling = -airCoupling(p, u, s, i) * s.velocity.get(i).dot(n) * n;  // the film moves with the air
  Vec3 f = internalForce(p, topo, s, i) + externalForce(p, u, pressure, s, i) + drag + coupling;
  if (u.closed) f += boyleForce(p, pressure, topo, s, i);
  s.force.set(i, f);
}

void externalForces(const Params& p, const StepUniforms& u, float pressure, State& s, size_t i) {
  s.force.set(i, externalForce(p, u, pressure, s, i));
}

// ---- integration ----------------------------------------------------------------------------------------

void integrate(const StepUniforms& u, const Topology& topo, State& s, size_t i) {
  if (!s.alive[i]) return;
  const Vec3 x = s.position.get(i);
  if (topo.boundary[i]) {
    if (s.wireParam[i] < 0.0f) {  // pinned where it is (the fixed rings of the validation scenes)
      s.velocity.set(i, Vec3::Zero());
      return;
    }
    const Vec3 xNext = wirePoint(wireNextOf(u), s.wireParam[i]);
    s.velocity.set(i, (xNext - x) / u.dt);
    s.position.set(i, xNext);
    return;
  }
  Vec3 v = s.velocity.get(i) + u.dt * s.force.get(i) / s.mass[i];  // Eq. (12)
  Vec3 xNew = x + u.dt * v;                                        // Eq. (13)
  if (xNew.y() < 0.0f) {  // the floor, y = 0: the film lands and slides, it does not pass through
    xNew.y() = 0.0f;
    v.y() = std::max(v.y(), 0.0f);
  }
  s.velocity.set(i, v);
  s.position.set(i, xNew);
}

// ---- drainage -------------------------------------------------------------------------------------------

float drainageDirection(const Vec3& xi, const Vec3& xj, const Vec3& g) {
  // Uphill or level (about half of a film's edges): no liquid runs that way, and no square roots are spent on it.
  const Vec3 d = xj - xi;
  const float along = d.dot(g);
  return along > 0 ? along / (d.norm() * g.norm()) : 0.0f;
}

void drainageOutflow(const Params& p, float dt, const Topology& topo, State& s, size_t i) {
  const Vec3 g(p.gravityX, p.gravityY, p.gravityZ), xi = s.position.get(i);
  float weight = 0.0f;
  for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k)
    weight += drainageDirection(xi, s.position.get(topo.springNeighbour[k]), g);
  s.drainWeight[i] = weight;
  s.drainOutflow[i] = s.liquid[i] * std::min(1.0f, dt * p.drainageRate * weight / p.sticky);
}

void drainageGather(const Params& p, const Topology& topo, State& s, size_t j) {
  const Vec3 g(p.gravityX, p.gravityY, p.gravityZ), xj = s.position.get(j);
  float received = 0.0f;
  for (uint32_t k = topo.springOffset[j]; k < topo.springOffset[j + 1]; ++k) {
    const uint32_t i = topo.springNeighbour[k];
    if (s.drainWeight[i] > 0)
      received += s.drainOutflow[i] * drainageDirection(s.position.get(i), xj, g) / s.drainWeight[i];
  }
  s.liquid[j] = s.liquid[j] - s.drainOutflow[j] + received;
}

// ---- film flow ------------------------------------------------------------------------------------------

namespace {

inline Vec3 tangential(const Vec3& v, const Vec3& n) { return v - v.dot(n) * n; }

}  // namespace

float flowAreaShare(const Topology& topo, const State& s, size_t i) {
  const uint32_t springs = topo.springOffset[i + 1] - topo.springOffset[i];
  return springs > 0 ? s.voronoiArea[i] / static_cast<float>(springs) : 0.0f;
}

float logSurfactant(const Params& p, float surfactant, float thickness) {
  return std::log(std::max(surfactant, kLeastSurfactant) *
                  (std::max(thickness, kThinnestFlowingFilm) / initialThickness(p)));
}

void filmFlowLogSurfactant(const Params& p, const State& s, size_t i, std::span<float> logSurfactant) {
  logSurfactant[i] = gb::logSurfactant(p, s.surfactant[i], s.thickness[i]);
}

FilmFlowTerms filmFlowTerms(const Params& p, const StepUniforms& u, const Topology& topo, const State& s, size_t i,
                            std::span<const float> logSurfactant) {
  FilmFlowTerms t;
  const Vec3 n = s.normal.get(i), xi = s.position.get(i);
  const float e = std::max(s.thickness[i], kThinnestFlowingFilm), rho = p.liquidDensity;
  Vec3 gradient = Vec3::Zero(), pull = Vec3::Zero();
  float weight = 0.0f, neighbours = 0.0f;
  for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
    const uint32_t j = topo.springNeighbour[k];
    if (!s.alive[j]) continue;
    const Vec3 d = s.position.get(j) - xi;
    const float d2 = d.squaredNorm();
    if (!(d2 > 0.0f)) continue;
    gradient += (logSurfactant[j] - logSurfactant[i]) / d2 * d;
    // u_j / |d|^2 and 1 / |d|^2 in the four lanes of one division: the same quotients as four (float_lanes.h)
    const Float4 q = Float4::of(s.flowVelocity.x[j], s.flowVelocity.y[j], s.flowVelocity.z[j], 1.0f) / Float4(d2);
    pull += Vec3(q.lane(0), q.lane(1), q.lane(2));
    weight += q.lane(3);
    neighbours += 1.0f;
  }
  t.gravity = tangential(Vec3(p.gravityX, p.gravityY, p.gravityZ), n);
  if (neighbours > 0.0f) {
    t.marangoni = -(p.marangoniElasticity / (rho * e)) * tangential((2.0f / neighbours) * gradient, n);
    t.viscosityRate = p.flowViscosity * (4.0f / neighbours) * weight;
    t.viscosityPull = p.flowViscosity * (4.0f / neighbours) * pull;
    t.spacingSquared = neighbours / weight;
  }
  const Vec3 airVelocity = u.wireArea > 0.0f ? Vec3(s.airFlow.get(i) / u.wireArea) : Vec3::Zero();
  t.air = tangential(airVelocity - s.velocity.get(i), n);
  t.airRate = 2.0f * p.airShear / (rho * e);
  t.wallRate = 12.0f * p.liquidViscosity * p.surfaceRigidity / (rho * e * e);
  return t;
}

void filmFlowVelocity(const Params& p, const StepUniforms& u, const Topology& topo, State& s, size_t i,
                      std::span<const float> logSurfactant) {
  s.flowAreaShare[i] = flowAreaShare(topo, s, i);  // once here, not in each of the ring's swept areas after
  if (!s.alive[i] || topo.boundary[i]) {
    s.flowVelocityNext.set(i, Vec3::Zero());
    return;
  }
  const float dt = u.drainageDt;
  const FilmFlowTerms t = filmFlowTerms(p, u, topo, s, i, logSurfactant);
  const float held = 1.0f + dt * (t.airRate + t.wallRate + t.viscosityRate);
  const float diffused =
      p.marangoniElasticity / (p.liquidDensity * std::max(s.thickness[i], kThinnestFlowingFilm)) * dt / held * dt;
  const float capped = kMarangoniCourant * t.spacingSquared;
  const float c = diffused > capped ? capped / diffused : 1.0f;
  const Vec3 driven = s.flowVelocity.get(i) + dt * (t.gravity + c * t.marangoni + t.airRate * t.air + t.viscosityPull);
  s.flowVelocityNext.set(i, tangential(driven / held, s.normal.get(i)));
}

float filmFlowSweptArea(float dt, const State& s, uint32_t i, uint32_t j) {
  const Vec3 d = s.position.get(j) - s.position.get(i);
  const float d2 = d.squaredNorm();
  if (!(d2 > 0.0f)) return 0.0f;
  return flowSweptArea(dt, s.flowAreaShare[i], s.flowAreaShare[j], s.flowVelocityNext.get(i).dot(d), d2);
}

namespace {

// The liquid particle i sends across an edge of which its velocity sweeps `swept` (m^3): filmFlowSent.
float sentOver(float swept, const State& s, uint32_t i) { return swept * s.thickness[i] * s.flowLimit[i]; }

}  // namespace

float filmFlowSent(float dt, const State& s, uint32_t i, uint32_t j) {
  return sentOver(filmFlowSweptArea(dt, s, i, j), s, i);
}

float filmFlowEdgeFlux(float dt, const State& s, uint32_t i, uint32_t j) {
  return filmFlowSent(dt, s, i, j) - filmFlowSent(dt, s, j, i);
}

void filmFlowLimit(const Params& p, float dt, const Topology& topo, State& s, size_t i, std::span<float> swept) {
  s.surfactantBefore[i] = s.surfactant[i];
  if (!s.alive[i]) {
    s.flowLimit[i] = 0.0f;
    return;
  }
  float sweptInAll = 0.0f;
  for (uint32_t k = topo.springOffset[i]; k < topo.springOffset[i + 1]; ++k) {
    const uint32_t j = topo.springNeighbour[k];
    if (!s.alive[j]) continue;
    const float area = filmFlowSweptArea(dt, s, static_cast<uint32_t>(i), j);
    swept[flowSweptSlot(topo, topo.springIndex[k], static_cast<uint32_t>(i))] = area;
    sweptInAll += area;
  }
  const float black = p.blackFilmThickness * s.voronoiArea[i];  // drainage stops at black film
  const float outflow = sweptInAll * s.thickness[i],
              allowed = kLargestOutflowShare * std::max(s.liquid[i] - black, 0.0f);
  s.flowLimit[i] = outflow > allowed ? allowed / outflow : 1.0f;
}

void filmFlowGather(const Params& p, float dt, const Topology& topo, State& s, size_t j, std::span<const float> swept) {
  s.flowVelocity.set(j, s.flowVelocityNext.get(j));
  if (!s.alive[j]) return;
  float liquidOut = 0.0f, surfactantOut = 0.0f;
  for (uint32_t k = topo.springOffset[j]; k < topo.springOffset[j + 1]; ++k) {
    const uint32_t i = topo.springNeighbour[k];
    if (!s.alive[i]) continue;
    const size_t own = flowSweptSlot(topo, topo.springIndex[k], static_cast<uint32_t>(j));
    const float sent = sentOver(swept[own], s, static_cast<uint32_t>(j));
    const float received = sentOver(swept[own ^ 1], s, i);
    liquidOut += sent - received;
    surfactantOut += sent * s.surfactantBefore[j] - received * s.surfactantBefore[i];
  }
  const float flowed = s.liquid[j] - liquidOut;
  const float liquid = flowed - evaporatedLiquid(p.evaporationRate, dt, flowed, s.voronoiArea[j], p.blackFilmThickness);
  const float surfactant = s.surfactantBefore[j] * s.liquid[j] - surfactantOut;  // evaporation leaves it behind
  s.liquid[j] = liquid;
  s.surfactant[j] = liquid > 0.0f ? surfactant / liquid : s.surfactantBefore[j];
}

// ---- stability ------------------------------------------------------------------------------------------

float elasticityBound(const Params& p) {
  const float youngX = 2.0f * initialThickness(p) / p.elasticityThickness;
  const float marangoni = 2.0f * youngX / (youngX + 2.0f);
  return p.elasticityWeight * std::max(0.5f, marangoni);
}

namespace {

// Physical model: the diagonal of the Hessian of i's triangle areas, sum_t |opposite edge|^2 / (4 A_t) (m^0);
// times the largest tension it bounds the stiffness the area force gives particle i.
float areaHessianDiagonal(const Topology& topo, const State& s, size_t i) {
  float sum = 0.0f;
  for (uint32_t k = topo.triangleOffset[i]; k < topo.triangleOffset[i + 1]; ++k) {
    const uint32_t corner = topo.triangleCorner[k], t = corner / 3, c = corner % 3;
    const uint32_t* tri = &topo.triangles[3 * t];
    const float twiceArea = s.triangleNormal.get(t).norm();
    const float edge2 = (s.position.get(tri[(c + 2) % 3]) - s.position.get(tri[(c + 1) % 3])).squaredNorm();
    if (twiceArea > 0) sum += edge2 / (2.0f * twiceArea);
  }
  return sum;
}

}  // namespace

float stableTimeStep(const Params& p, const Topology& topo, const State& s, float pressure, float volume) {
  const float eMax = elasticityBound(p);
  const float tensionMax = highestTension(p.surfaceTension);
  float dt = std::numeric_limits<float>::infinity();
  const bool closed = topo.isClosed();
  // The air coupling's frame area Area_wm is at most the film's area: the film spans the planar wire frame.
  float filmArea = 0.0f;
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i]) filmArea += s.voronoiArea[i];
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s.alive[i] || topo.boundary[i] || s.mass[i] <= 0) continue;
    const float springs = static_cast<float>(topo.springOffset[i + 1] - topo.springOffset[i]);
    // Gershgorin: row sum of |K| is at most twice the diagonal; up to 6 collision contacts at a time.
    const float filmStiffness = p.tensionModel == 1 ? tensionMax * areaHessianDiagonal(topo, s, i) : springs * eMax;
    float stiffness = 2.0f * (filmStiffness + 6.0f * p.collisionStiffness);
    if (closed && volume > 0) stiffness += pressure * s.voronoiArea[i] * s.voronoiArea[i] / volume;
    const float omega = std::sqrt(stiffness / s.mass[i]);
    const float airCouplingMax = closed ? 0.0f : fullAirCoupling(p, filmArea, s.voronoiArea[i]);
    const float damping = (2.0f * (springs * p.springDamping + 6.0f * p.collisionDamping) +
                           p.airDrag * s.voronoiArea[i] + airCouplingMax) /
                          s.mass[i];
    dt = std::min(dt, 2.0f / (omega + damping));
  }
  return p.stabilitySafety * dt;
}

}  // namespace gb
