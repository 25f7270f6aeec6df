#include "simulation/simulation.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "solver/implicit_euler.h"
#include "topology/collision.h"
#include "topology/film_checks.h"
#include "topology/film_growth.h"

namespace gb {

namespace {

// Sums leaf(i) over i in [0, n) with add(sums, leaf) in parallel and in a fixed order: each block of kBlock indices
// in index order, then the blocks' sums in block order. The rounding depends on n alone, never on the thread count
// or the schedule (the same figures on every machine), and no thread waits on a serial pass over the film: on a
// million particles a serial pass cost most of the statistics' time.
template <class Sums, class Leaf, class Add>
Sums sumInBlocks(size_t n, Leaf&& leaf, Add&& add) {
  constexpr size_t kBlock = size_t{1} << 12;
  const size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<Sums> partial(blocks);
#pragma omp parallel for schedule(static) if (blocks > 1)
  for (long b = 0; b < static_cast<long>(blocks); ++b) {
    const size_t first = static_cast<size_t>(b) * kBlock, last = std::min(n, first + kBlock);
    Sums sums{};
    for (size_t i = first; i < last; ++i) add(sums, leaf(i));
    partial[static_cast<size_t>(b)] = sums;
  }
  Sums total{};
  for (const Sums& sums : partial) add(total, sums);
  return total;
}

// Adds the particles' part of the frame's sums: their count, energies, liquid, thickness and air flow, and the
// largest speed.
void addParticleSums(FilmSums& sums, const FilmSums& more) {
  sums.particles += more.particles;
  sums.kinetic += more.kinetic;
  sums.potential += more.potential;
  sums.liquid += more.liquid;
  sums.thickness += more.thickness;
  sums.airFlow += more.airFlow;
  sums.maxSpeed = std::max(sums.maxSpeed, more.maxSpeed);
}

// Eq. (5)'s MAX(cos(theta), 0): how alike the two wands' velocities are. A wand at rest has no direction;
// the moving one then blows on its own (factor 1).
float wandAlignment(const WandState& w) {
  const float norms = w.leftVelocity.norm() * w.rightVelocity.norm();
  if (norms <= 1e-12f) return 1.0f;
  return std::max(w.leftVelocity.dot(w.rightVelocity) / norms, 0.0f);
}

Vec3 gravityOf(const Params& p) { return {p.gravityX, p.gravityY, p.gravityZ}; }

// The frame's sums over the film in host memory (Simulation::stats), in double; cone volumes to `origin`.
FilmSums sumFilm(const Params& params, const Film& film, const Vec3& origin) {
  const State& s = film.state;
  const Topology& topo = film.topology;
  const Eigen::Vector3d g = gravityOf(params).cast<double>();
  FilmSums sums = sumInBlocks<FilmSums>(
      s.size(),
      [&](size_t i) {
        FilmSums p;
        if (!s.alive[i]) return p;
        const Eigen::Vector3d v = s.velocity.get(i).cast<double>();
        p.particles = 1;
        p.kinetic = 0.5 * s.mass[i] * v.squaredNorm();
        p.potential = -liquidMass(params, s.liquid[i]) * g.dot(s.position.get(i).cast<double>());
        p.liquid = s.liquid[i];
        p.thickness = s.thickness[i];
        p.airFlow = s.airFlow.get(i).norm();
        p.maxSpeed = v.norm();
        return p;
      },
      addParticleSums);
  const auto addDouble = [](double& sum, double more) { sum += more; };
  if (params.tensionModel == 1) {
    sums.elastic = sumInBlocks<double>(
        s.size(),
        [&](size_t i) {
          return s.alive[i] ? filmTensionEnergy(params, surfactantLiquid(params, s.mass[i]), s.voronoiArea[i]) : 0.0;
        },
        addDouble);
  } else {
    sums.elastic = sumInBlocks<double>(
        topo.springCount(),
        [&](size_t k) {
          const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
          const double stretch = (s.position.get(a) - s.position.get(b)).cast<double>().norm() - topo.restLength[k];
          return springEnergyOf<double>(springStiffness(s, a, b), stretch);
        },
        addDouble);
  }
  using AreaVolume = std::array<double, 2>;
  const AreaVolume areaVolume = sumInBlocks<AreaVolume>(
      topo.triangleCount(),
      [&](size_t t) {
        const uint32_t* tri = &topo.triangles[3 * t];
        const Eigen::Vector3d a = (s.position.get(tri[0]) - origin).cast<double>();
        const Eigen::Vector3d b = (s.position.get(tri[1]) - origin).cast<double>();
        const Eigen::Vector3d c = (s.position.get(tri[2]) - origin).cast<double>();
        return AreaVolume{0.5 * (b - a).cross(c - a).norm(), a.dot(b.cross(c)) / 6.0};
      },
      [](AreaVolume& sum, const AreaVolume& more) {
        sum[0] += more[0];
        sum[1] += more[1];
      });
  sums.area = areaVolume[0];
  sums.volume = areaVolume[1];
  return sums;
}

using Clock = std::chrono::steady_clock;

double millisecondsBetween(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

// The merges of a frame on which they are due: up to `rounds` rounds, one for each frame since the last
// (Params::mergeInterval; a round merges no two particles of one one-ring), so that they keep up with the film as when
// they run every frame.
size_t mergeCrowdedParticlesInRounds(const Params& params, Film& film, SpringEnergyAllowance& allowance, int rounds) {
  size_t merged = 0;
  for (int round = 0; round < rounds; ++round) {
    const size_t more = mergeCrowdedParticles(params, film, allowance);
    if (more == 0) break;
    merged += more;
  }
  return merged;
}

}  // namespace

Simulation::Simulation(const Params& params, const WandTool& tool, const WandState& wands,
                       std::unique_ptr<Stepper> stepper)
    : Simulation(params, generateFilm(params, tool, wands), wands, std::move(stepper)) {}

Simulation::Simulation(const Params& params, Film film, const WandState& wands, std::unique_ptr<Stepper> stepper)
    : params_(params),
      film_(std::move(film)),
      stepper_(std::move(stepper)),
      wands_(wands),
      contactHorizon_(params.frameTime) {
  if (const auto errors = validate(params_); !errors.empty()) throw std::invalid_argument(errors.front());
  if (!stepper_) stepper_ = std::make_unique<CpuStepper>();
  CpuStepper::refreshGeometry(params_, film_);
  if (film_.topology.isClosed() && film_.referenceVolume <= 0) {
    film_.volumeOrigin = centroid(film_.state);
    film_.referenceVolume = CpuStepper().volume(film_, film_.volumeOrigin);
  }
  pressure_ = params_.pressureCoefficient;
  chooseSubsteps();
  stepper_->load(params_, film_);
  updateContacts();
  readbackRecorded_ = deviceReadback();
}

void Simulation::chooseSubsteps() {
  if (params_.integrator != 0) {  // implicit: stable at any step, so the frame is split only when asked
    substeps_ = params_.implicitSubsteps;
    return;
  }
  const float volume = film_.topology.isClosed() ? film_.referenceVolume : 0.0f;
  const float dtStable = stableTimeStep(params_, film_.topology, film_.state, params_.pressureCoefficient, volume);
  const double needed = std::ceil(params_.frameTime / dtStable);
  if (!(needed <= params_.maxSubsteps)) {
    std::ostringstream msg;
    msg << "the film needs " << needed << " substeps per frame to stay stable (maxSubsteps = " << params_.maxSubsteps
        << "): use fewer particles (particlesAtFullSolution), more filmInertia, or a shorter frameTime";
    throw std::invalid_argument(msg.str());
  }
  substeps_ = std::max(1, static_cast<int>(needed));
}

Vec3 Simulation::loopHang() const { return film_.loopHang.norm() > 0 ? film_.loopHang : gravityOf(params_); }

WireFrame Simulation::frameHanging(const WandState& wands, const Vec3& hang) const {
  return makeWireFrame(film_.tool, wands, film_.stringLength, hang);
}

// The way the loop hangs once the tips reach `next`: swung towards gravity at Params::loopSwingRate at most.
Vec3 Simulation::loopHangAfter(const WandState& next) const {
  if (film_.tool.kind != ToolKind::TwoWands) return loopHang();
  return swingLoop(loopHang(), spanAxis(next), gravityOf(params_), params_.loopSwingRate * params_.frameTime);
}

StepUniforms Simulation::uniformsFor(const WandState& a, const WandState& b, float dt) const {
  return uniformsBetween(a, b, dt, loopHang(), loopHang());
}

StepUniforms Simulation::uniformsBetween(const WandState& a, const WandState& b, float dt, const Vec3& hangA,
                                         const Vec3& hangB) const {
  StepUniforms u;
  u.dt = dt;
  WandState sources = a;
  // Eq. (5) has a source at each end of the frame. The ring's one hand moves its whole frame, both ends at once:
  // it blows as two wands held together there would (the air a frame pushes is set by the frame's motion, not by
  // how many hands hold it), both sources at the hand, aligned.
  if (film_.tool.kind == ToolKind::Ring) {
    sources.leftPosition = a.rightPosition;
    sources.leftVelocity = a.rightVelocity;
  }
  setWands(u, sources);
  u.leftInflowWeight = 1.0f;
  u.wandAlignment = wandAlignment(sources);
  const WireFrame frameNow = frameHanging(a, hangA);
  u.wireArea = frameNow.area();
  u.airVolume = frameNow.height() * u.wireArea;  // Eq. (6)
  setWireNext(u, frameHanging(b, hangB));
  u.closed = film_.topology.isClosed() ? 1u : 0u;
  u.volumeOrigin = toVec4(u.closed ? film_.volumeOrigin : frameNow.center);
  u.referenceVolume = film_.referenceVolume;
  return u;
}

void Simulation::setFrameTime(float h) {
  if (!(h > 0.0f && h <= 0.1f))
    throw std::invalid_argument("frame time " + std::to_string(h) + " s is not in (0, 0.1]");
  if (h == params_.frameTime) return;
  pullState();  // the substeps follow the film's stable step
  params_.frameTime = h;
  chooseSubsteps();
  if (h > contactHorizon_) {  // from now on contacts reach as far as the longest step: not searched again each time
    contactHorizon_ = h;      // the live loop alternates short and long steps
    updateContacts();
  }
}

void Simulation::setParams(const Params& params) {
  if (const auto errors = validate(params); !errors.empty()) throw std::invalid_argument(errors.front());
  const Params before = params_;
  params_ = params;
  params_.frameTime = before.frameTime;
  try {
    reloadFilm();
  } catch (const std::invalid_argument&) {  // too many explicit substeps: the old parameters stay
    params_ = before;
    reloadFilm();
    throw;
  }
}

void Simulation::advanceFrame(const WandState& next) {
  geometryFresh_ = false;
  burstOnHardImpact();  // judged on the contacts found after the last frame, before this one moves them
  const float dt = params_.frameTime / static_cast<float>(substeps_);
  const float wandSpeed =
      std::max((next.leftPosition - wands_.leftPosition).norm(), (next.rightPosition - wands_.rightPosition).norm()) /
      params_.frameTime;
  const Vec3 hangNow = loopHang(), hangNext = loopHangAfter(next);
  const auto hangAt = [&](float t) { return Vec3(((1 - t) * hangNow + t * hangNext).normalized()); };
  substepUniforms_.clear();
  for (int k = 0; k < substeps_; ++k) {
    const float t0 = static_cast<float>(k) / static_cast<float>(substeps_);
    const float t1 = static_cast<float>(k + 1) / static_cast<float>(substeps_);
    substepUniforms_.push_back(
        uniformsBetween(interpolate(wands_, next, t0), interpolate(wands_, next, t1), dt, hangAt(t0), hangAt(t1)));
    substepUniforms_.back().solverSweeps = solverSweeps_;
  }
  substepUniforms_.back().drainageDt = params_.frameTime;  // the frame's drainage, after its last substep
  const long loadsBefore = loads_;
  const auto started = Clock::now();
  pressure_ = stepper_->run(substepUniforms_);
  stateOnDevice_ = positionsOnDevice_ = device() != nullptr;  // the step's state is the device's until brought back
  refreshOnPull_ = false;
  checksForNextFrame_.reset();
  heldChecks_.reset();
  if (const VelocityBudget& budget = stepper_->lastBudget(); budget.acted()) {
    ++budgetRecord_.frames;
    budgetRecord_.smallestScale = std::min(budgetRecord_.smallestScale, budget.scale);
    budgetRecord_.largestShift = std::max(budgetRecord_.largestShift, budget.shift.norm());
  }
  stepCount_ += substeps_;
  framesSinceMerge_ = film_.topology.isClosed() ? framesSinceMerge_ + 1 : 0;
  wands_ = next;
  film_.loopHang = hangNext;
  time_ += params_.frameTime;
  // The rules between steps read the state in host memory: it comes back only when the device's checks say one of
  // them may act.
  heldForARegion_ = false;
  heldRule_ = nullptr;
  const bool passed = stateStaysOnDevice_ && passesOnDevice(next, wandSpeed);
  if (!passed && !heldForARegion_) pullState();
  const auto stepped = Clock::now();
  if (passed) {
    ++readbackRecord_.framesPassed;
  } else if (heldForARegion_) {
    applyRulesWhereTheyLie(next, wandSpeed);
  } else {
    applyRulesBetweenSteps(next, wandSpeed);
  }
  if (mergeDue()) framesSinceMerge_ = 0;  // its turn taken, on whichever path the frame went
  const auto changed = Clock::now();
  updateContacts();
  phases_ = {millisecondsBetween(started, stepped), millisecondsBetween(stepped, changed),
             millisecondsBetween(changed, Clock::now())};
  aerosol_.advance(params_, params_.frameTime);
  recordReadback(loadsBefore);
}

bool Simulation::passesOnDevice(const WandState& next, float wandSpeed) {
  std::optional<FilmChecks> checks = checksOnDevice(false);
  if (!checks) return false;
  if (ruleThatMayAct(*checks, next, wandSpeed, false)) {
    heldChecks_ = checks;  // of the film as the step left it, for the rules on the CPU (the contraction's sums)
  } else {
    // The rest-length rules the device runs itself may still act: there. The payout widens the wire's band, which
    // the checks then measure again for a new ring (growFilmAtWire looks for one after its payout).
    const bool yielded = checks->yielding > 0 && yieldApplies() && device()->yieldStretchedSprings();
    SpringEnergyAllowance allowance{stepper_->lastBudget().released};
    const bool contracted = checks->slack > 0 && contractionApplies() && contractOnDevice(*checks, allowance);
    const bool paidOut = checks->rungsPastGrowth > 0 && payoutApplies(wandSpeed) && device()->payOutFilmAtWire();
    if (paidOut) checks = checksOnDevice(false);
    if (yielded) checks->yielding = 0;  // its springs now at the yield stretch, within the checks' margin
    if (contracted) checks->slack = 0;  // taken as far as the allowance pays
    if (paidOut) checks->rungsPastGrowth = 0;
    restLengthsOnDevice_ = restLengthsOnDevice_ || yielded || paidOut;
  }
  if (const char* rule = ruleThatMayAct(*checks, next, wandSpeed, true)) {
    ++readbackRecord_.framesHeldByRule[rule];
    heldRule_ = rule;
    heldForARegion_ = aRegionServes(*checks, next, wandSpeed);
    if (heldForARegion_) regionChecks_ = *checks;
    return false;
  }
  if (bodyTouchesFilm()) {  // the body's touch is tested on the film in host memory
    ++readbackRecord_.framesHeldByRule["touch"];
    return false;
  }
  for (int w = 0; w < 2; ++w)  // burstOnWandTouch's arming, far from its threshold (ruleThatMayAct)
    wandArmed_[w] = wandArmed_[w] || checks->nearestTip[w] > params_.pinchDistance;
  events_ = {};
  return true;
}

void Simulation::applyRulesBetweenSteps(const WandState& next, float wandSpeed) {
  checkStable();
  burstOnWandTouch();
  touchByBody();
  burstOnFloorTouch();
  events_ = advanceBurst(params_, time_, film_, burst_, aerosol_);
  if (events_.particlesRemoved > 0) takeShrunkMesh();
  if (!burst_.active()) applyRulesOfAnUnbrokenFilm(next, wandSpeed);
  if (tipsTogether(next) && !film_.topology.isClosed() && !burst_.active()) events_.pinchedOff = pinch();
}

void Simulation::applyRulesWhereTheyLie(const WandState& next, float wandSpeed) {
  const FilmChecks& checks = regionChecks_;
  events_ = {};
  if (film_.topology.isClosed() && !burst_.active()) {  // burstOnWandTouch, whose test the checks say cannot pass
    for (int w = 0; w < 2; ++w) wandArmed_[w] = wandArmed_[w] || checks.nearestTip[w] > params_.pinchDistance;
  }
  if (!burst_.active() && mayTouchTheFloor(checks)) {
    device()->storeParticleArrays(film_, {&film_.state.position});  // what burstOnFloorTouch reads
    positionsOnDevice_ = false;
    burstOnFloorTouch();
  }
  advanceBurstWhereItLies(checks);
  if (!burst_.active()) applyRulesOfAnUnbrokenFilm(next, wandSpeed);
  if (tipsTogether(next) && !film_.topology.isClosed() && !burst_.active()) events_.pinchedOff = pinch();
}

void Simulation::advanceBurstWhereItLies(const FilmChecks& checks) {
  State& s = film_.state;
  DeviceResidency& d = *device();
  if (mayCrackByThinning(checks)) {
    d.storeParticleArrays(film_, {&s.thickness, &s.voronoiArea});  // what the crack's test reads
    crackWhereThin(params_, time_, film_, burst_);
  }
  // What the front reads, asked for until it asks no more: each time with rings around what it asked for, since a
  // front that reads further may reach further; twice as many rings each time, as a fast rim crosses many a frame.
  std::vector<char> readable(s.size(), 0);
  int rings = 1;
  for (std::vector<uint32_t> unread = particlesTheFrontReads(params_, time_, film_, burst_, readable); !unread.empty();
       unread = particlesTheFrontReads(params_, time_, film_, burst_, readable), rings *= 2) {
    for (uint32_t i : unread) readable[i] = 1;
    for (size_t ring = 0, from = 0; ring < static_cast<size_t>(rings); ++ring) {
      const size_t to = unread.size();
      for (size_t u = from; u < to; ++u)
        for (uint32_t k = film_.topology.springOffset[unread[u]]; k < film_.topology.springOffset[unread[u] + 1]; ++k)
          if (const uint32_t j = film_.topology.springNeighbour[k]; !readable[j]) {
            readable[j] = 1;
            unread.push_back(j);
          }
      from = to;
    }
    std::sort(unread.begin(), unread.end());
    if (!d.storeParticleArraysOf(film_, unread, {&s.position, &s.velocity, &s.liquid, &s.thickness}, {})) {
      pullState();  // a stepper that brings back only the whole state
      break;
    }
  }
  if (restLengthsOnDevice_ && frontReachesThisFrame()) {
    d.storeRestLengths(film_);  // the springs the front leaves keep their rest lengths
    restLengthsOnDevice_ = false;
  }
  events_ = advanceFront(params_, time_, film_, burst_, aerosol_);
  if (events_.particlesRemoved > 0) takeShrunkMesh();
}

bool Simulation::frontReachesThisFrame() const {
  const State& s = film_.state;
  if (burst_.arrival.size() != s.size()) return false;  // no crack scheduled since the film last changed its size
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i] && burst_.arrival[i] <= time_) return true;
  return false;
}

void Simulation::takeShrunkMesh() {
  DeviceResidency* d = device();
  if (d && d->updateTopology(params_, film_)) return;
  pullState();  // the state the device stepped, for a load
  stepper_->load(params_, film_);
}

void Simulation::applyRulesOfAnUnbrokenFilm(const WandState& next, float wandSpeed) {
  // Only a film being drawn yields: a free bubble's wobbles are elastic, so it rounds up again instead of
  // keeping every dent its momentum makes. A free bubble contracts where it goes slack instead: the long bag it
  // was drawn as holds about 1.6 times the surface of a sphere of its air, which otherwise hangs in wrinkles
  // (and fills the contact lists). The open bag is not contracted: it is slack where the air has not yet filled
  // it, and there it is still being drawn.
  if (yieldApplies()) yieldStretchedSpringsWhereTheyLie();
  // What contraction and merging add to the springs, the step's dissipation pays (SpringEnergyAllowance). The
  // merges, which remake the mesh and reload the stepper, run every mergeInterval frames.
  SpringEnergyAllowance allowance{stepper_->lastBudget().released};
  if (contractionApplies()) contractSlackSpringsWhereTheyLie(allowance);
  if (mergeDue()) mergeCrowdedParticlesWhereTheyLie(allowance);
  growFilm(next, wandSpeed);
}

void Simulation::mergeCrowdedParticlesWhereTheyLie(SpringEnergyAllowance& allowance) {
  CrowdedCandidates candidates;
  if (!stateOnDevice_ || params_.tensionModel != 0 || !device()->findCrowdedSprings(candidates)) {
    pullState();  // the film in host memory, or a stepper that does not find the merges' springs
    if (mergeCrowdedParticlesInRounds(params_, film_, allowance, params_.mergeInterval) > 0) reloadFilm();
    return;
  }
  // The state stayed on the device, which finds what each round tries. What the round reads comes back, and the
  // device takes what it changed; the geometry is made anew after the last round, as the CPU's reload makes it.
  std::vector<char> inHostMemory(film_.state.size(), 0);  // as the CPU's merges find it this frame
  bool merged = false;
  for (int round = 0; round < params_.mergeInterval; ++round) {
    if (round > 0 && !device()->findCrowdedSprings(candidates)) {  // the device took every change so far
      finishMergesInHostMemory(allowance, params_.mergeInterval - round);
      return;
    }
    if (candidates.springs.empty()) break;
    bringBackWhatAMergeRoundReads(candidates.springs, inHostMemory);
    std::vector<CrowdedSpring> tried = crowdedSpringsAmong(params_, film_, candidates.springs);
    keepTheMergeable(tried, std::sqrt(candidates.medianSquaredLength));
    const std::vector<Merge> merges = chooseMerges(film_, tried);
    if (merges.empty()) break;
    std::vector<uint32_t> particles;  // whose whole state the merges read and write
    for (const Merge& m : merges) particles.insert(particles.end(), {m.survivor, m.joining});
    std::sort(particles.begin(), particles.end());
    device()->storeRegion(film_, particles, {});
    std::vector<uint32_t> from;
    makeMerges(params_, film_, merges, allowance, &from);
    if (!device()->updateMergedRegion(params_, film_, particles, from))  // a stepper with no film loaded
      throw std::logic_error("Simulation: a stepper that found the merges' springs takes their changes");
    merged = true;
  }
  if (!merged) return;
  device()->refreshGeometry();
  checksForNextFrame_.reset();  // of the film before it changed
  ++loads_;
  geometryFresh_ = false;  // in host memory only the merges' regions: stats() probes the device's
  chooseSubsteps();
}

void Simulation::finishMergesInHostMemory(SpringEnergyAllowance& allowance, int rounds) {
  pullState();
  mergeCrowdedParticlesInRounds(params_, film_, allowance, rounds);
  reloadFilm();
}

void Simulation::bringBackWhatAMergeRoundReads(std::span<const uint32_t> springs, std::vector<char>& inHostMemory) {
  const Topology& topo = film_.topology;
  std::vector<uint32_t> unread;
  const auto read = [&](uint32_t i) {
    if (inHostMemory[i]) return;
    inHostMemory[i] = 1;
    unread.push_back(i);
  };
  for (const uint32_t k : springs)
    for (const uint32_t end : {topo.springEnds[2 * k], topo.springEnds[2 * k + 1]}) {
      read(end);
      for (uint32_t r = topo.springOffset[end]; r < topo.springOffset[end + 1]; ++r) read(topo.springNeighbour[r]);
    }
  std::sort(unread.begin(), unread.end());
  State& s = film_.state;
  device()->storeParticleArraysOf(film_, unread, {&s.position, &s.thickness, &s.elasticity},
                                  restLengthsOnDevice_ ? springs : std::span<const uint32_t>{});
}

void Simulation::yieldStretchedSpringsWhereTheyLie() {
  if (device() && device()->yieldStretchedSprings()) {
    restLengthsOnDevice_ = true;
    return;
  }
  pullState();
  if (yieldStretchedSprings(params_, film_) > 0) updateDeviceRestLengths();
}

bool Simulation::aRegionServes(const FilmChecks& checks, const WandState& next, float wandSpeed) const {
  // The explicit integrator's substeps read the state; the body's touch reads the whole film.
  if (params_.integrator == 0 || bodyTouchesFilm()) return false;
  FilmChecks others = checks;
  others.yielding = 0;  // the rest-length rules run where the state lies
  others.slack = 0;
  others.rungsPastGrowth = 0;
  others.lowest = std::numeric_limits<float>::infinity();    // the floor's test reads the positions alone,
  others.thinnest = std::numeric_limits<float>::infinity();  // the crack's the thickness and area
  if (checks.unstable) return false;
  if (burst_.active()) return true;  // the burst alone acts on a film it takes (applyRulesBetweenSteps)
  // Beside a crack scheduled (its front the region), nothing but the floor or a crack by thinning, or a ring at the
  // wire (the tips not together for a pinch-off), or the merges (a closed film: no ring, no pinch-off).
  const char* rule = ruleBesideTheBurst(others, next, wandSpeed, true);
  const std::string_view first = rule == nullptr ? "" : rule;
  return rule == nullptr || (first == "ring" && !tipsTogether(next)) || first == "merge";
}

bool Simulation::tipsTogether(const WandState& wands) const {
  return film_.tool.kind == ToolKind::TwoWands &&
         (wands.rightPosition - wands.leftPosition).norm() < params_.pinchDistance;
}

DeviceReadback Simulation::deviceReadback() const { return device() ? device()->readback() : DeviceReadback{}; }

void Simulation::updateDeviceRestLengths() {
  if (DeviceResidency* d = device()) d->updateRestLengths(film_);
}

void Simulation::recordReadback(long loadsBefore) {
  // Since the last frame's record: this frame's copies and those made between the frames, for the statistics and
  // whatever read film() (the outputs, the renderer's framing).
  const DeviceReadback before = std::exchange(readbackRecorded_, deviceReadback());
  const DeviceReadback& now = readbackRecorded_;
  const uint64_t bytes = now.bytes - before.bytes;
  const bool burstScheduled = burst_.cause != nullptr && burst_.finished < 0;  // a crack to come, or one opening
  const bool topologyEvent = burstScheduled || events_.started || events_.finished || events_.particlesRemoved > 0 ||
                             events_.pinchedOff || events_.particlesAdded > 0 || loads_ != loadsBefore;
  ReadbackRecord& r = readbackRecord_;
  ++r.frames;
  r.stateReadbacks += now.stateReadbacks - before.stateReadbacks;
  r.bytes += bytes;
  if (heldRule_) {
    r.stateReadbacksHeldByRule[heldRule_] += now.stateReadbacks - before.stateReadbacks;
    r.bytesHeldByRule[heldRule_] += bytes;
  }
  if (!topologyEvent) {
    ++r.framesWithoutEvent;
    r.bytesWithoutEvent += bytes;
  }
}

std::optional<FilmChecks> Simulation::checksOnDevice(bool atPresentPositions) {
  FilmProbe probe;
  probe.tips = {wands_.leftPosition, wands_.rightPosition};
  probe.frameTime = params_.frameTime;
  probe.atPresentPositions = atPresentPositions;
  FilmSums sums;
  FilmChecks checks;
  if (!device() || !device()->probeFilm(probe, sums, checks)) return std::nullopt;
  return checks;
}

void Simulation::contractSlackSpringsWhereTheyLie(SpringEnergyAllowance& allowance) {
  // Where the stepper checks the film on its device, the contraction runs there with the share its sums give, as on
  // the frames that pass the checks: a frame ends with the same film whichever way it went. The checks that held
  // the frame describe the film still, unless the burst took particles since.
  std::optional<FilmChecks> checks = events_.particlesRemoved == 0 ? heldChecks_ : std::nullopt;
  if (!checks) checks = checksOnDevice(false);
  if (checks && checks->slack == 0) return;  // the checks, loosened towards acting, find no slack spring
  if (checks && contractOnDevice(*checks, allowance)) {
    if (!stateOnDevice_) pullState();  // the rest lengths, for the merges (which bring them back where they lie)
    return;
  }
  pullState();
  if (contractSlackSprings(params_, film_, allowance) > 0) updateDeviceRestLengths();
}

bool Simulation::contractOnDevice(const FilmChecks& checks, SpringEnergyAllowance& allowance) {
  const float quadratic = checks.contractionQuadratic, linear = checks.contractionLinear;
  const float share = contractionShareOf(quadratic, linear, allowance.joules);
  if (!device() || !device()->contractSlackSprings(share)) return false;
  allowance.joules -= contractionEnergyOf(share, quadratic, linear);
  restLengthsOnDevice_ = true;
  return true;
}

bool Simulation::contractionApplies() const { return film_.topology.isClosed() && params_.tensionModel == 0; }

bool Simulation::mergeDue() const { return film_.topology.isClosed() && framesSinceMerge_ >= params_.mergeInterval; }

bool Simulation::yieldApplies() const {
  return !film_.topology.isClosed() && params_.tensionModel == 0 && params_.yieldStretch > 1.0f;
}

const char* Simulation::ruleThatMayAct(const FilmChecks& c, const WandState& next, float wandSpeed,
                                       bool deviceRules) const {
  if (c.particles == 0) return nullptr;                                // the film is gone
  if (c.unstable) return "unstable";                                   // checkStable
  if (burst_.cause != nullptr && burst_.finished < 0) return "burst";  // a crack scheduled, or a burst under way
  return ruleBesideTheBurst(c, next, wandSpeed, deviceRules);
}

bool Simulation::mayTouchTheFloor(const FilmChecks& c) const {
  return c.lowest < kFloorTouching * (1.0f + kFilmCheckMargin);
}

bool Simulation::mayCrackByThinning(const FilmChecks& c) const {
  return c.thinnest < params_.thicknessThreshold * (1.0f + kFilmCheckMargin);
}

const char* Simulation::ruleBesideTheBurst(const FilmChecks& c, const WandState& next, float wandSpeed,
                                           bool deviceRules) const {
  constexpr float m = kFilmCheckMargin;
  const Params& p = params_;
  const Topology& topo = film_.topology;
  if (mayTouchTheFloor(c)) return "floor";       // burstOnFloorTouch
  if (mayCrackByThinning(c)) return "thinning";  // advanceBurst: a crack by thinning
  if (topo.isClosed()) {  // burstOnWandTouch; the winding number is 0 or 1, its float sum within 5% of it
    for (int w = 0; w < 2; ++w) {
      const float d = c.nearestTip[w];
      if (!wandArmed_[w] ? std::abs(d - p.pinchDistance) <= m * p.pinchDistance
                         : d < p.collisionDistance * (1.0f + m) || !(c.winding[w] <= 0.45f))
        return "wand";
    }
  }
  if (deviceRules && yieldApplies() && c.yielding > 0) return "yield";
  // The merges are asked before the contraction, although the CPU runs the contraction first: a frame they hold is
  // named by them, the one rule of the two that the device cannot run.
  if (mergeDue() && p.tensionModel == 0 && c.crowded > 0) return "merge";
  if (deviceRules && contractionApplies() && c.slack > 0) return "contraction";
  // growFilm: the payout, and a new ring once the band is wide enough.
  if (deviceRules && wandSpeed >= kDrawingSpeed && film_.wireLiquid > 0.0f && c.rungsPastGrowth > 0) return "payout";
  if (wireBandWidthOf(c.rungRest, c.rungs, c.wireEdgeLength, c.wireEdges) >= kRingInsertionWidth * (1.0f - m))
    return "ring";
  return tipsTogether(next) && !topo.isClosed() ? "pinch" : nullptr;
}

void Simulation::pullState() const {
  if (restLengthsOnDevice_) {
    device()->storeRestLengths(film_);
    restLengthsOnDevice_ = false;
  }
  if (stateOnDevice_) {
    device()->store(film_);
    stateOnDevice_ = positionsOnDevice_ = false;
    if (refreshOnPull_) CpuStepper::refreshGeometry(params_, film_);  // as stats() leaves a film in host memory
  }
  if (contactsOnDevice_) {
    device()->storeContacts(film_);
    contactsOnDevice_ = false;
    contactHistory_ = {film_.topology.contacts, film_.state.size()};
  }
}

const Film& Simulation::filmPositionsOnly() const {
  if (positionsOnDevice_) {
    device()->storePositions(film_);
    positionsOnDevice_ = false;
  }
  return film_;
}

void Simulation::burstOnHardImpact() {
  if (burst_.active() || params_.collisionThreshold <= 0.0f) return;
  if (stateOnDevice_ || contactsOnDevice_) {  // the device's checks first: the state comes back near an impact
    const std::optional<FilmChecks> checks = checksForNextFrame_ ? checksForNextFrame_ : checksOnDevice(false);
    if (checks && checks->hardestImpact <= params_.collisionThreshold * (1.0f - kFilmCheckMargin)) return;
    pullState();
  }
  const Impact impact = hardestImpact(params_, params_.frameTime, film_);
  if (impact.number > params_.collisionThreshold) startCrack(burst_, film_, impact.particle, time_, "impact");
}

void Simulation::burstOnWandTouch() {
  if (!film_.topology.isClosed() || burst_.active()) return;
  const Vec3 tips[2] = {wands_.leftPosition, wands_.rightPosition};
  for (int w = 0; w < 2; ++w) {
    const Nearest nearest = nearestParticle(film_.state, tips[w]);
    if (!wandArmed_[w]) {
      wandArmed_[w] = nearest.distance > params_.pinchDistance;  // pulled clear of the bubble it let go of
    } else if (nearest.distance < params_.collisionDistance || insideClosedFilm(film_, tips[w])) {
      startCrack(burst_, film_, nearest.particle, time_, "wand");
      return;
    }
  }
}

void Simulation::setBody(const BodyPoints& body) {
  if (body.time == bodyTime_ && touch_.hasBody()) return;  // the same depth frame: its grid is built
  touch_.setBody(body);
  bodyTime_ = body.time;
}

bool Simulation::bodyTouchesFilm() const {
  return touch_.hasBody() && !burst_.active() && (film_.topology.isClosed() || params_.touchWireFilm != 0);
}

void Simulation::touchByBody() {
  if (!bodyTouchesFilm()) return;
  touch_.setHands(params_.wetHands != 0, params_.touchStrikeSpeed);  // live parameters: as they are this frame
  const std::vector<Touch> touching = touch_.touches(film_.state, touchArmed_, !film_.topology.isClosed());
  if (touching.empty()) return;
  if (const std::optional<Touch> burst = touch_.burstingTouch(touching)) {
    startCrack(burst_, film_, burst->particle, time_, "touch");
    lastTouch_ = burst;
  } else if (touch_.push(film_.state, touching) > 0) {
    stepper_->load(params_, film_);  // wet hands moved the film: the stepper takes it as it now is
    ++loads_;
  }
}

void Simulation::burstOnFloorTouch() {
  // A soap film bursts on a dry floor: the step lets particles land on y = 0 (and slide), this pops them.
  if (burst_.active()) return;
  const State& s = film_.state;
  for (uint32_t i = 0; i < s.size(); ++i)
    if (s.alive[i] && s.position.get(i).y() < kFloorTouching) {
      startCrack(burst_, film_, i, time_, "floor");
      return;
    }
}

bool Simulation::payoutApplies(float wandSpeed) const {
  return wandSpeed >= kDrawingSpeed && film_.wireLiquid > 0.0f && wireLoopIntact(film_);
}

void Simulation::growFilm(const WandState& wands, float wandSpeed) {
  const bool paidOnDevice = payoutApplies(wandSpeed) && device() && device()->payOutFilmAtWire();
  if (paidOnDevice) restLengthsOnDevice_ = true;
  // What the ring insertion reads: where the state stayed on the device, the region it reads (with the rest lengths
  // there where the device's rules changed them); otherwise the state and the rest lengths the device's rules
  // changed, which the payout uploads.
  const FilmRegion region = stateOnDevice_ ? wireGrowthRegion(film_) : FilmRegion{};
  const bool inRegion =
      stateOnDevice_ &&
      device()->storeRegion(film_, region.particles, restLengthsOnDevice_ ? region.springs : std::vector<uint32_t>{});
  if (!inRegion) pullState();
  const size_t firstParticle = film_.state.size(), firstSpring = film_.topology.springCount();
  const WireFrame frame = wireFrame(wands);
  const GrowthEvent grew = growFilmAtWire(params_, frame, wandSpeed, film_, !paidOnDevice);
  events_.particlesAdded = grew.particlesAdded;
  if (inRegion && (grew.particlesAdded > 0 || grew.restLengthsChanged > 0))
    reloadRegion(region, firstParticle, firstSpring);
  else if (grew.particlesAdded > 0)
    reloadFilm();
  else if (grew.restLengthsChanged > 0)
    updateDeviceRestLengths();
}

void Simulation::reloadRegion(const FilmRegion& region, size_t firstParticle, size_t firstSpring) {
  checksForNextFrame_.reset();  // of the film before it changed
  ++loads_;
  geometryFresh_ = false;  // in host memory only the region's: stats() probes the device's
  chooseSubsteps();
  if (!device() ||
      !device()->updateRegion(params_, film_, region.particles, firstParticle, region.springs, firstSpring))
    throw std::logic_error("Simulation: a stepper that brings back regions takes them back too");
}

void Simulation::reloadFilm() {
  pullState();
  checksForNextFrame_.reset();  // of the film before it changed
  ++loads_;
  CpuStepper::refreshGeometry(params_, film_);
  geometryFresh_ = true;
  chooseSubsteps();
  stepper_->load(params_, film_);
}

void Simulation::updateContacts() {
  checksForNextFrame_.reset();  // its impact test read the last list
  // Contacts for the next frame: within reach of what two particles can close in the longest step taken so far,
  // plus 5 mm for what the step's forces add to their start velocities.
  constexpr float slack = 0.005f;
  // A stepper that searches on its device keeps the list there for its sweeps (and brings it back with the state);
  // otherwise the CPU searches.
  if (device() && device()->findContactsOnDevice(params_, contactHorizon_, slack, contactHistory_)) {
    contactsOnDevice_ = true;
    contactHistory_ = {{}, film_.state.size(), true};
    if (!stateStaysOnDevice_) pullState();
    return;
  }
  pullState();
  contactSearch_.find(params_, contactHorizon_, slack, film_, contactHistory_);
  if (DeviceResidency* d = device()) d->updateContacts(film_);
  contactHistory_ = {film_.topology.contacts, film_.state.size()};
}

void Simulation::startBurst(size_t particle) {
  pullState();
  startCrack(burst_, film_, particle, time_, "poke");
}

size_t Simulation::topParticle() const {
  pullState();
  const State& s = film_.state;
  size_t best = 0;
  float bestY = -std::numeric_limits<float>::infinity();
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i] && !film_.topology.boundary[i] && s.position.y[i] > bestY) {
      bestY = s.position.y[i];
      best = i;
    }
  return best;
}

bool Simulation::pinch() {
  // A film the burst took whole has nothing left to pinch.
  if (film_.topology.isClosed() || burst_.active() || film_.topology.triangleCount() == 0) return false;
  pullState();
  try {
    if (!pinchOff(params_, film_)) return false;
  } catch (const std::runtime_error&) {
    return false;  // a torn boundary: the burst will take it
  }
  // The wands' air is shut in: it moves with the bubble now. Left in place, the air transfer would carry it
  // round the closed film for ever (no wire feeds or drains it), pushing the bubble out of shape.
  for (size_t i = 0; i < film_.state.size(); ++i) {
    film_.state.airFlow.set(i, Vec3::Zero());
    film_.state.airInflow.set(i, Vec3::Zero());
    film_.state.airFlowNext.set(i, Vec3::Zero());
  }
  burst_ = BurstFront{};
  wandArmed_ = {false, false};  // the tips are at the seam: they count once they have left the bubble
  reloadFilm();
  return true;
}

void Simulation::dip(const WandState& wands) {
  film_ = generateFilm(params_, film_.tool, wands);
  stateOnDevice_ = positionsOnDevice_ = contactsOnDevice_ = restLengthsOnDevice_ = false;  // the old film's, replaced
  contactHistory_ = {};  // the new film's particles are not the old one's
  burst_ = BurstFront{};
  lastTouch_.reset();
  touchArmed_.clear();  // the new film's particles have not yet been clear of the body
  wands_ = wands;
  reloadFilm();
}

void Simulation::checkStable() const {
  const State& s = film_.state;
  const auto stable = [&](size_t i) { return !s.alive[i] || particleStable(s.position.get(i), s.velocity.get(i)); };
  // The first unstable particle, found in parallel (the lowest index whatever the threads).
  const auto count = static_cast<long>(s.size());
  long first = count;
#pragma omp parallel for schedule(static) reduction(min : first) if (count >= (long{1} << 16))
  for (long i = 0; i < count; ++i)
    if (!stable(static_cast<size_t>(i))) first = std::min(first, i);
  if (first < count) {
    const auto i = static_cast<size_t>(first);
    const Vec3 x = s.position.get(i), v = s.velocity.get(i);
    std::ostringstream msg;
    msg << "simulation unstable at t = " << time_ << " s (step " << stepCount_ << "): particle " << i
        << (x.allFinite() && v.allFinite() ? " moves faster than 100 m/s" : " has a non-finite position or velocity")
        << "; lower stabilitySafety or frameTime, or check the parameters";
    throw SimulationUnstable(msg.str());
  }
}

FrameStats Simulation::stats() {
  const Topology& topo = film_.topology;
  FrameStats st;
  st.time = time_;
  st.triangles = topo.triangleCount();
  // The cone volumes' apex: a closed film's volume does not depend on it (the device takes the bubble's fixed
  // origin, the CPU its centroid, which keeps the float differences small); an open film's swept volume is the cone
  // to the frame's centre.
  const Vec3 frameCentre = wireFrame(wands_).center;
  FilmProbe probe;
  probe.origin = topo.isClosed() ? film_.volumeOrigin : frameCentre;
  probe.tips = {wands_.leftPosition, wands_.rightPosition};
  probe.frameTime = params_.frameTime;
  FilmSums sums;
  FilmChecks checks;
  if (device() && device()->probeFilm(probe, sums, checks)) {
    checksForNextFrame_ = checks;  // of the film the next frame starts from: its impact test
    // The device refreshed its geometry: so does the film in host memory, now or when it comes back.
    if (stateOnDevice_)
      refreshOnPull_ = true;
    else if (!geometryFresh_)
      CpuStepper::refreshGeometry(params_, film_);
  } else {
    // The film's geometry as it stands after the step, for the sums on the CPU and for what reads the film after
    // them (the outputs, the renderer).
    pullState();
    if (!geometryFresh_) CpuStepper::refreshGeometry(params_, film_);
    sums = sumFilm(params_, film_, topo.isClosed() ? centroid(film_.state) : frameCentre);
  }
  st.particles = sums.particles;
  st.area = sums.area;
  st.volume = sums.volume;
  st.kineticEnergy = sums.kinetic;
  st.elasticEnergy = sums.elastic;
  st.potentialEnergy = sums.potential;
  st.liquid = sums.liquid;
  st.maxSpeed = sums.maxSpeed;
  st.meanThickness = st.particles ? sums.thickness / static_cast<double>(st.particles) : 0;
  st.meanAirFlow = st.particles ? sums.airFlow / static_cast<double>(st.particles) : 0;
  st.solution = film_.solutionLeft(params_);
  st.droplets = aerosol_.size();
  for (float m : aerosol_.mass) st.dropletMass += m;
  return st;
}

}  // namespace gb
