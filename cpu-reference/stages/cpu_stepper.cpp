#include "stages/cpu_stepper.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>

#include "solver/colouring.h"
#include "solver/energy_budget.h"
#include "solver/implicit_euler.h"

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

// Runs body(first, last) over [0, count) in blocks of kFourBlock, the blocks in parallel: for the stages that
// compute four triangles or springs at a time in the lanes of float_lanes.h. Every block starts at a multiple of
// four, so its fours are those that a call per four would compute, the same floats, for a sixteenth of the calls.
constexpr size_t kFourBlock = 64;
// The blocks [first(b), last(b)) of kFourBlock indices that [0, count) splits into.
struct FourBlocks {
  size_t count;
  [[nodiscard]] size_t size() const { return (count + kFourBlock - 1) / kFourBlock; }
  [[nodiscard]] static size_t first(size_t b) { return kFourBlock * b; }
  [[nodiscard]] size_t last(size_t b) const { return std::min(count, kFourBlock * b + kFourBlock); }
};
template <class Body>
void forEachFour(size_t count, Body&& body) {
  const FourBlocks blocks{count};
  forEach(blocks.size(), [&](size_t b) { body(FourBlocks::first(b), blocks.last(b)); });
}

// Each particle's N terms (terms(i), computed in parallel into `scratch`), each summed over the particles in the
// fixed tree order (treeSum) that the GPU's tree sums follow.
template <size_t N, class Terms>
std::array<float, N> treeSumsOf(std::array<std::vector<float>, N>& scratch, size_t n, Terms terms) {
  for (std::vector<float>& column : scratch) column.resize(n);
  forEach(n, [&](size_t i) {
    const std::array<float, N> t = terms(i);
    for (size_t c = 0; c < N; ++c) scratch[c][i] = t[c];
  });
  std::array<float, N> sums{};
  for (size_t c = 0; c < N; ++c) sums[c] = treeSumInPlace(scratch[c]);
  return sums;
}

}  // namespace

template <class Body>
void CpuStepper::timed(Stage stage, Body&& body) {
  if (!timing_) return body();
  const auto start = std::chrono::steady_clock::now();
  body();
  times_[static_cast<int>(stage)] +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void CpuStepper::load(const Params& params, Film& film) {
  params_ = &params;
  film_ = &film;
  lastBudget_ = {};
  drift_ = Vec3::Zero();
  ensureColouring(film.state.alive, film.topology);
  if (params.coarseIterations > 0) ensurePatches(film.state.alive, params.coarsePatchRings, film.topology);
}

float CpuStepper::volume(const Film& film, const Vec3& origin) { return volumeOf(film, origin, false); }

float CpuStepper::volumeOf(const Film& film, const Vec3& origin, bool atStepStart) {
  const size_t triangles = film.topology.triangleCount();
  triangleVolumes_.resize(triangles);
  forEachFour(triangles, [&](size_t first, size_t last) {
    triangleVolumes(film.topology, film.state, origin, atStepStart, first, last, triangleVolumes_.data());
  });
  return treeSumInPlace(triangleVolumes_);
}

void CpuStepper::refreshGeometry(const Params& params, Film& film) {
  State& s = film.state;
  fitTriangleArrays(film.topology, s);
  forEachFour(film.topology.triangleCount(),
              [&](size_t first, size_t last) { triangleGeometries(film.topology, s, first, last); });
  forEach(s.size(), [&](size_t i) {
    vertexGeometry(film.topology, s, i);
    filmState(params, 0.0f, s, i);
  });
  film.geometryKey = geometryKey(film.topology, s);
}

float CpuStepper::runStage(Stage stage, const StepUniforms& u) {
  if (!film_) throw std::logic_error("CpuStepper: no film loaded");
  State& s = film_->state;
  const Topology& topo = film_->topology;
  const size_t n = s.size();
  float result = 0.0f;
  timed(stage, [&] {
    switch (stage) {
      case Stage::Geometry: {  // two passes: every triangle is done before any particle gathers
        const uint64_t key = geometryKey(topo, s);
        if (key == film_->geometryKey && s.cornerArea.size() == 3 * topo.triangleCount()) break;  // computed
        fitTriangleArrays(topo, s);
        forEachFour(topo.triangleCount(), [&](size_t first, size_t last) { triangleGeometries(topo, s, first, last); });
        forEach(n, [&](size_t i) { vertexGeometry(topo, s, i); });
        film_->geometryKey = key;
        break;
      }
      case Stage::Volume:
        result = volume(*film_, toVec3(u.volumeOrigin));
        break;
      case Stage::FilmState:
        forEach(n, [&](size_t i) { filmState(params(), u.dt, s, i); });
        break;
      case Stage::AirInflow:
        forEach(n, [&](size_t i) { airInflow(params(), u, s, i); });
        break;
      case Stage::AirTransfer:
        forEach(n, [&](size_t i) { airTransfer(params(), topo, s, i); });
        std::swap(s.airFlow, s.airFlowNext);  // Jacobi: the new air becomes the front buffer
        break;
      case Stage::Forces:
        forEach(n, [&](size_t i) { forces(params(), u, currentPressure(u), topo, s, i); });
        break;
      case Stage::Integrate:
        forEach(n, [&](size_t i) { integrate(u, topo, s, i); });
        break;
      case Stage::ExternalForces:
        forEach(n, [&](size_t i) { externalForces(params(), u, currentPressure(u), s, i); });
        break;
      case Stage::ExternalDrift:
        drift_ = filmDrift();
        break;
      case Stage::ImplicitPredict: {
        const Vec3 drift = u.closed ? drift_ : Vec3::Zero();
        forEach(n, [&](size_t i) { implicitPredict(u, topo, drift, s, i); });
        break;
      }
      case Stage::CoarseCorrection:
        correctCoarsely(u);
        break;
      case Stage::VertexBlockDescent:
        sweep(u);
        break;
      case Stage::EnergyBudget:
        lastBudget_ = budgetEnergy(u);
        result = lastBudget_.scale;
        break;
      case Stage::ImplicitVelocity: {
        forEach(n, [&](size_t i) { implicitVelocity(u, topo, lastBudget_, s, i); });
        break;
      }
      case Stage::Drainage:  // two Jacobi passes: every outflow is known before anyone gathers
        forEach(n, [&](size_t i) { drainageOutflow(params(), u.drainageDt, topo, s, i); });
        forEach(n, [&](size_t i) { drainageGather(params(), topo, s, i); });
        break;
      case Stage::FilmFlow:  // Jacobi passes: the logs, new velocities, then every limit, then the gathers
        flowLogSurfactant_.resize(n);
        forEach(n, [&](size_t i) { filmFlowLogSurfactant(params(), s, i, flowLogSurfactant_); });
        forEach(n, [&](size_t i) { filmFlowVelocity(params(), u, topo, s, i, flowLogSurfactant_); });
        flowSwept_.resize(2 * topo.springCount());
        forEach(n, [&](size_t i) { filmFlowLimit(params(), u.drainageDt, topo, s, i, flowSwept_); });
        forEach(n, [&](size_t i) { filmFlowGather(params(), u.drainageDt, topo, s, i, flowSwept_); });
        break;
      case Stage::Count:
        break;
    }
  });
  if (stage == Stage::Volume) {
    lastVolume_ = result;
    if (stepping_) stepStartVolume_ = result;
  }
  return result;
}

void CpuStepper::sweep(const StepUniforms& u) {
  layOutSweepRuns(params(), u, film_->topology, film_->state, sweepRuns_);
  const int sweeps = sweepsThisStep(params(), u), before = coarseSweepsBefore(params(), u);
  if (before < 0) return runSweeps(u, 0, sweeps);
  runSweeps(u, 0, before);
  runStage(Stage::CoarseCorrection, u);
  runSweeps(u, before, sweeps);
}

void CpuStepper::runSweeps(const StepUniforms& u, int from, int to) {
  State& s = film_->state;
  const Topology& topo = film_->topology;
  const SweepRuns& runs = sweepRuns_;
  Bubble bubble;
  const FourBlocks blocks{topo.triangleCount()};  // forEachFour's, in the sweeps' own parallel region
  if (u.closed) triangleVolumes_.resize(blocks.count);
    // One parallel region for the sweeps: the colours still wait for each other (the barrier closing each
    // omp for), but the threads are woken once, not once per colour and sweep.
#pragma omp parallel
  for (int sweep = from; sweep < to; ++sweep) {
    if (u.closed) {  // Boyle's pressure at this iterate's volume, as volume() takes it: the triangles on every
                     // thread, their sum on one, in the fixed order both backends add in
#pragma omp for schedule(static)
      for (long b = 0; b < static_cast<long>(blocks.size()); ++b)
        triangleVolumes(topo, s, toVec3(u.volumeOrigin), false, FourBlocks::first(static_cast<size_t>(b)),
                        blocks.last(static_cast<size_t>(b)), triangleVolumes_.data());
#pragma omp single
      {
        lastVolume_ = treeSumInPlace(triangleVolumes_);  // first: Boyle's pressure reads it
        bubble = bubbleOf(lastVolume_, currentPressure(u));
      }
    }
    for (size_t c = 0; c + 1 < runs.colourRuns.size(); ++c) {  // colours in order
      const auto first = static_cast<long>(runs.colourRuns[c]), last = static_cast<long>(runs.colourRuns[c + 1]);
#pragma omp for schedule(static)
      for (long r = first; r < last; ++r)
        vertexBlockDescentRun(params(), u, bubble, topo, s, runs, static_cast<uint32_t>(r));
    }
  }
}

void CpuStepper::correctCoarsely(const StepUniforms& u) {
  State& s = film_->state;
  const Topology& topo = film_->topology;
  if (topo.patchOffset.empty()) return;  // the correction is off: no patches were made
  Bubble bubble;
  if (u.closed) {  // Boyle's pressure at this iterate's volume, as a sweep takes it
    lastVolume_ = volume(*film_, toVec3(u.volumeOrigin));  // first: Boyle's pressure reads it
    bubble = bubbleOf(lastVolume_, currentPressure(u));
  }
  fitCoarseSystem(topo, coarse_);
  forEach(coarse_.shortestSpring.size(),
          [&](size_t patch) { coarseAssemble(params(), u, bubble, topo, s, patch, coarse_); });
  coarseSolve(topo, params().coarseIterations, coarse_);
  forEach(s.size(), [&](size_t i) { coarseApply(topo, coarse_, s, i); });
}

VelocityBudget CpuStepper::budgetEnergy(const StepUniforms& u) {
  const State& s = film_->state;
  const Topology& topo = film_->topology;
  const size_t pieces = heldPieceCount(params(), topo);
  heldPieces_.start.resize(pieces);
  heldPieces_.end.resize(pieces);
  forEachFour(pieces, [&](size_t first, size_t last) { heldPieces(params(), topo, s, first, last, heldPieces_); });
  const std::array<float, GB_ENERGY_TERMS> sums = treeSumsOf(energyTerms_, s.size(), [&](size_t i) {
    const ParticleEnergy e = energyTerms(params(), u, topo, s, heldPieces_, i);
    return std::array<float, GB_ENERGY_TERMS>{e.start,        e.kinetic,      e.held,         e.mass,
                                              e.momentum.x(), e.momentum.y(), e.momentum.z(), e.expected.x(),
                                              e.expected.y(), e.expected.z()};
  });
  float gas = 0.0f;
  if (u.closed) {  // the volumes before and after the step, as the volume stage sums them
    // The budget places particles on the wire at their end position (positionAtStepStart): the volume stage's sum
    // at the step's start is the budget's "before" only where there are none.
    const float before =
        stepStartVolume_ && !topo.hasBoundary() ? *stepStartVolume_ : volumeOf(*film_, toVec3(u.volumeOrigin), true);
    lastVolume_ = volume(*film_, toVec3(u.volumeOrigin));
    gas = boyleEnergyChange(params(), u.referenceVolume, before, lastVolume_);
  }
  return energyScale(sums[0], sums[1], sums[2] + gas, sums[3], Vec3(sums[4], sums[5], sums[6]),
                     Vec3(sums[7], sums[8], sums[9]));
}

Vec3 CpuStepper::filmDrift() {
  return driftAcceleration(treeSumsOf(driftTerms_, film_->state.size(),
                                      [&](size_t i) { return externalDrift(film_->topology, film_->state, i); }));
}

float CpuStepper::currentPressure(const StepUniforms& u) const {
  return u.closed ? boylePressure(params(), u.referenceVolume, lastVolume_) : params().pressureCoefficient;
}

float CpuStepper::step(const StepUniforms& u) {
  lastBudget_ = {};  // the energy budget's stage sets it where it runs; implicit_velocity applies it
  stepping_ = true;
  stepStartVolume_.reset();
  for (const StageSpec& spec : stepStages())
    if (spec.runs(params(), u)) runStage(spec.stage, u);
  stepping_ = false;
  stepStartVolume_.reset();
  return currentPressure(u);
}

float CpuStepper::run(std::span<const StepUniforms> substeps) {
  float pressure = params().pressureCoefficient;
  for (const StepUniforms& u : substeps) pressure = step(u);
  return pressure;
}

}  // namespace gb
