#pragma once
// What every backend offers the simulation: the same stages, in the same order, with the same semantics
// (docs/architecture.md). CpuStepper (here) is the reference; VulkanStepper (host/) runs the stages as compute
// shaders and is checked against it.

#include <array>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>

#include "energy_budget.h"
#include "film.h"
#include "film_checks.h"
#include "shared_step.h"
#include "stages.h"

namespace gb {

struct ContactHistory;  // collision.h

// The stages a step can run. Their order, when each runs and the barrier after each are stepStages().
enum class Stage : int {
  Geometry,
  Volume,
  FilmState,
  AirInflow,
  AirTransfer,
  Forces,              // explicit integrator: internal + external forces
  Integrate,           // explicit integrator: Eqs. (12)-(13)
  ExternalForces,      // implicit integrator: the forces kept explicit (gravity, air, Boyle pressure)
  ExternalDrift,       // implicit integrator, closed film: the acceleration the explicit forces give its centre of mass
  ImplicitPredict,     // implicit integrator: x_t kept, wire placed, first guess
  VertexBlockDescent,  // implicit integrator: solverSweeps sweeps over the colours, the coarse correction
                       // after the first half of them (coarseSweepsBefore)
  CoarseCorrection,    // implicit integrator: the iterate corrected by rigid moves of patches (coarse_correction.h);
                       // recorded inside vertex_block_descent, run alone only by tests and benchmarks
  EnergyBudget,        // implicit integrator: the factor on the new velocities that keeps the step's energy within
                       // the work done on the film (energy_budget.h)
  ImplicitVelocity,    // implicit integrator: v = (x - x_t) / h, the free particles' as the energy budget leaves them
  Drainage,            // filmFlow 0: the paper's position-dependent drainage, Eqs. (14)-(15)
  FilmFlow,            // filmFlow 1: the thin-film flow (stages.h)
  Count
};
inline constexpr int kStageCount = static_cast<int>(Stage::Count);

// One row of the step: the stage, its name (the C++ stage, its GLSL kernel(s) and the tests use it), when it
// runs, the device's buffers it reads and writes (bits of gpu::Binding, kernels/shared/device_data.h), and why a
// barrier follows it (nullptr: no stage before the next barrier reads what it wrote or writes what it read; a test
// checks this against the buffers).
struct StageSpec {
  Stage stage;
  const char* name;
  bool (*runs)(const Params& params, const StepUniforms& uniforms);
  uint32_t reads, writes;
  const char* barrierAfter;
};
// The set of the device's buffers `bindings`, as bits.
constexpr uint32_t bufferSet(std::initializer_list<gpu::Binding> bindings) {
  uint32_t bits = 0;
  for (const gpu::Binding b : bindings) bits |= 1u << b;
  return bits;
}
// The one list of the step's stages, in order: CpuStepper::step, VulkanStepper's recording and both
// backends' timing walk it (docs/architecture.md "The step's stages").
std::span<const StageSpec> stepStages();
const char* stageName(Stage stage);

// Time spent per stage (ms) since the last reset; filled when timing is enabled.
using StageTimes = std::array<double, kStageCount>;

// What a stepper has copied from its device into host memory since it was made: whole-state read-backs (store)
// and the bytes of every copy (the state, the contact list, the reductions' few floats). None for a stepper that
// works in host memory.
struct DeviceReadback {
  size_t stateReadbacks = 0;
  uint64_t bytes = 0;
};

// The frame's sums over the film (Simulation::stats, FrameStats): the living particles, their energies, liquid,
// thickness and air flow, the springs' or the film tension's energy, the triangles' area and cone volume, and the
// largest speed.
struct FilmSums {
  size_t particles = 0;
  double kinetic = 0, potential = 0, liquid = 0, thickness = 0, airFlow = 0, elastic = 0, area = 0, volume = 0;
  double maxSpeed = 0;
};

class Stepper {
 public:
  virtual ~Stepper() = default;
  [[nodiscard]] virtual std::string name() const = 0;

  // Takes a film (new, or changed by a topology event): its whole state and topology. The CPU stepper
  // steps this Film object in place; a GPU stepper copies it to the device.
  virtual void load(const Params& params, Film& film) = 0;
  // Runs the substeps in order (one submission on the GPU). Returns the Boyle pressure of the last one
  // (Eq. 11; P_0 for an open film).
  virtual float run(std::span<const StepUniforms> substeps) = 0;
  // Runs one stage alone on the loaded film (equivalence tests, per-stage benchmarks). Returns the volume
  // for Stage::Volume, the velocity factor for Stage::EnergyBudget, 0 otherwise. AirTransfer includes the
  // Jacobi swap.
  virtual float runStage(Stage stage, const StepUniforms& uniforms) = 0;
  // Brings the per-particle state back into the film given to load (nothing to do on the CPU).
  virtual void store(Film& film) = 0;
  // Brings back only the particles' positions (a renderer drawing the stepper's buffers in place frames the film
  // from them): by default the whole state.
  virtual void storePositions(Film& film) { store(film); }
  // Brings back the per-particle arrays of film.state listed (by address) for every particle: what a rule between
  // steps reads of the whole film (the merges choose by the positions, thickness and elasticity). By default the
  // whole state.
  virtual void storeParticleArrays(Film& film, std::initializer_list<const void*> /*arrays*/) { store(film); }
  // Takes the film's new self-collision contact list (Topology::contacts), found between frames.
  virtual void updateContacts(const Film&) {}
  // Finds the film's self-collision contacts for the next frame itself, the list findContacts makes with the same
  // arguments (collision.h), and leaves it in film.topology.contacts too. Returns false when the stepper leaves the
  // search to the caller (findContacts on the CPU, then updateContacts), as the CPU stepper does.
  virtual bool findContacts(const Params&, float /*frameTime*/, float /*slack*/, Film&, const ContactHistory&) {
    return false;
  }
  // Takes a film whose mesh changed but whose particles did not move or change (a burst removed springs and
  // triangles and flagged particles dead): a GPU stepper writes only the topology and the alive flags and
  // keeps its state. By default, and whenever the particle count changed, it is a load().
  virtual void updateTopology(const Params& params, Film& film) { load(params, film); }
  // Takes the film's changed spring rest lengths (the wire paying out film between frames, film_growth.h).
  virtual void updateRestLengths(const Film&) {}
  // Brings back a region of the film where a rule between steps reads it, not the whole state: the per-particle state
  // store() brings back, of the particles listed, and the rest lengths of the springs listed (both ascending). False
  // where the stepper brings back nothing by regions (the caller then calls store()), as the CPU stepper does.
  virtual bool storeRegion(Film&, std::span<const uint32_t> /*particles*/, std::span<const uint32_t> /*springs*/) {
    return false;
  }
  // Takes a film that a rule between steps changed in a region and may have grown (film growth at the wire appends
  // particles, springs and triangles, old indices staying): the per-particle arrays of the particles listed and of
  // those from firstNewParticle on, the rest lengths of the springs listed and of those from firstNewSpring on, and the
  // mesh's connectivity. Everything else the stepper holds stays, its state included, and its contact list stays the
  // history of the next search. False where the stepper takes only whole films (the caller then calls load()).
  virtual bool updateRegion(const Params&, Film&, std::span<const uint32_t> /*particles*/, size_t /*firstNewParticle*/,
                            std::span<const uint32_t> /*springs*/, size_t /*firstNewSpring*/) {
    return false;
  }

  // What the energy budget did in the last step run (the last substep of run()): nothing (VelocityBudget{}) when
  // the step kept within its budget or no budget ran (energy_budget.h).
  [[nodiscard]] const VelocityBudget& lastBudget() const { return lastBudget_; }

  // Sums and checks the film where the stepper holds it (FilmSums, and FilmChecks of film_checks.h with its
  // thresholds loosened by kFilmCheckMargin), the cone volumes to probe.origin: a GPU stepper reduces them on the
  // device and reads back a few floats. With probe.atPresentPositions the geometry and film state are first brought up
  // to the present positions, as the statistics want; without, the checks see them as the last step left them, as
  // the rules between steps read them. Returns false when the caller sums and checks the film in host memory, as the
  // CPU stepper's caller does.
  virtual bool probeFilm(const FilmProbe& /*probe*/, FilmSums&, FilmChecks&) { return false; }
  // Finds the contacts as findContacts does but leaves the list on the device, for the sweeps (storeContacts brings
  // it into film.topology.contacts when the CPU needs it); the list's entries are counted in host memory. False when
  // the stepper leaves the search to the caller.
  virtual bool findContactsOnDevice(const Params&, float /*frameTime*/, float /*slack*/, const ContactHistory&) {
    return false;
  }
  virtual void storeContacts(Film&) {}
  // Runs a rest-length rule between steps on the rest lengths on the device, from the state as the last step left it:
  // the yield of stretched springs, or the wire's payout (yieldStretchedSprings and payOutFilmAtWire of
  // film_growth.h, with the same tests). They change there, and storeRestLengths brings them into
  // film.topology.restLength. False when the caller runs the rule on the film in host memory (and uploads the rest
  // lengths with updateRestLengths).
  virtual bool yieldStretchedSprings() { return false; }
  virtual bool payOutFilmAtWire() { return false; }
  // The same for the contraction of a closed film's slack springs (contractSlackSprings), each `share` of the way
  // (contractionShareOf: the caller weighs the checks' contractionEnergy against the allowance).
  virtual bool contractSlackSprings(float /*share*/) { return false; }
  virtual void storeRestLengths(Film&) {}
  [[nodiscard]] virtual DeviceReadback readback() const { return {}; }

  virtual void enableTiming(bool on) { timing_ = on; }
  [[nodiscard]] const StageTimes& stageTimes() const { return times_; }
  void resetStageTimes() { times_.fill(0.0); }

 protected:
  bool timing_ = false;
  StageTimes times_{};
  VelocityBudget lastBudget_;
};

}  // namespace gb
