#pragma once
// What every backend offers the simulation: the same stages, in the same order, with the same semantics
// (docs/architecture.md). CpuStepper (here) is the reference; VulkanStepper (host/) runs the stages as compute
// shaders and is checked against it.

#include <array>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>

#include "kernels/shared/shared_step.h"
#include "model/film.h"
#include "solver/energy_budget.h"
#include "stages/stages.h"

namespace gb {

class DeviceResidency;  // device_residency.h

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

class Stepper {
 public:
  virtual ~Stepper() = default;
  [[nodiscard]] virtual std::string name() const = 0;

  // Takes a film (new, or changed by a topology event): its whole state and topology. The CPU stepper
  // steps this Film object in place; a GPU stepper copies it to the device. The parameters stay the caller's
  // (Simulation's, the one live copy): the stepper reads them at each step, so a change to them reaches the next
  // step's stages. Both must outlive the stepper's use of them.
  virtual void load(const Params& params, Film& film) = 0;
  // Runs the substeps in order (one submission on the GPU). Returns the Boyle pressure of the last one
  // (Eq. 11; P_0 for an open film).
  virtual float run(std::span<const StepUniforms> substeps) = 0;
  // Runs one stage alone on the loaded film (equivalence tests, per-stage benchmarks). Returns the volume
  // for Stage::Volume, the velocity factor for Stage::EnergyBudget, 0 otherwise. AirTransfer includes the
  // Jacobi swap.
  virtual float runStage(Stage stage, const StepUniforms& uniforms) = 0;
  // What the caller must do for a stepper whose film lives on a device, and what it may leave to it
  // (device_residency.h); null for a stepper that steps the film in host memory, as the CPU stepper does.
  [[nodiscard]] virtual DeviceResidency* device() { return nullptr; }

  // What the energy budget did in the last step run (the last substep of run()): nothing (VelocityBudget{}) when
  // the step kept within its budget or no budget ran (energy_budget.h).
  [[nodiscard]] const VelocityBudget& lastBudget() const { return lastBudget_; }

  void enableTiming(bool on) { timing_ = on; }
  [[nodiscard]] const StageTimes& stageTimes() const { return times_; }
  void resetStageTimes() { times_.fill(0.0); }

 protected:
  bool timing_ = false;
  StageTimes times_{};
  VelocityBudget lastBudget_;
};

}  // namespace gb
