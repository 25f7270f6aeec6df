#include "cpu_stepper.h"

#include <utility>

namespace gb {

namespace {

// Runs body(i) for every index in parallel. Stages write only element i, so any schedule gives the same
// result.
template <class Body>
void forEach(size_t n, Body&& body) {
  const auto count = static_cast<long>(n);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < count; ++i) body(static_cast<size_t>(i));
}

}  // namespace

float CpuStepper::volume(const Film& film, const Vec3& origin) {
  triangleVolumes_.resize(film.topology.triangleCount());
  forEach(triangleVolumes_.size(),
          [&](size_t t) { triangleVolumes_[t] = triangleSignedVolume(film.topology, film.state, t, origin); });
  return treeSum(triangleVolumes_);
}

void CpuStepper::refreshGeometry(const Params& params, Film& film) {
  State& s = film.state;
  forEach(s.size(), [&](size_t i) {
    computeVertexGeometry(film.topology, s, i);
    updateFilmState(params, 0.0f, s, i);
  });
}

float CpuStepper::step(const Params& params, const StepUniforms& u, Film& film) {
  State& s = film.state;
  const Topology& topo = film.topology;
  const size_t n = s.size();

  forEach(n, [&](size_t i) { computeVertexGeometry(topo, s, i); });               // 2. geometry
  const float pressure = u.closed ? boylePressure(params, u.referenceVolume, volume(film, u.volumeOrigin))
                                  : params.pressureCoefficient;                   //    volume reduction
  forEach(n, [&](size_t i) { updateFilmState(params, u.dt, s, i); });             // 3. film state
  forEach(n, [&](size_t i) { computeAirInflow(params, u, s, i); });               // 4. air inflow
  forEach(n, [&](size_t i) { transferAirFlow(params, topo, s, i); });             // 5. air transfer
  std::swap(s.airFlow, s.airFlowNext);                                            //    Jacobi swap
  forEach(n, [&](size_t i) { computeForces(params, u, pressure, topo, s, i); });  // 6. forces
  forEach(n, [&](size_t i) { integrateParticle(u, topo, s, i); });                // 7. integration
  return pressure;
}

}  // namespace gb
