#pragma once
// The CPU backend: one step walks stepStages() (stepper.h), each stage run over all elements in parallel
// (OpenMP), on the host film in place. The Vulkan stepper records the same table as dispatches.

#include <array>
#include <optional>
#include <vector>

#include "solver/coarse_correction.h"
#include "solver/energy_budget.h"
#include "solver/implicit_euler.h"
#include "stages/stepper.h"

namespace gb {

class CpuStepper final : public Stepper {
 public:
  [[nodiscard]] std::string name() const override { return "cpu"; }
  void load(const Params& params, Film& film) override;
  float run(std::span<const StepUniforms> substeps) override;
  float runStage(Stage stage, const StepUniforms& uniforms) override;

  // Geometry (normals, Voronoi areas) and the film state from the current positions, without stepping.
  static void refreshGeometry(const Params& params, Film& film);
  // Enclosed (closed film) or swept (open film, cone to the origin) volume with the fixed-shape tree sum.
  float volume(const Film& film, const Vec3& origin);

 private:
  float step(const StepUniforms& u);
  // Stage vertex_block_descent: the sweeps of the implicit step, colour after colour, a colour's particles in
  // parallel (implicit_euler.h).
  void sweep(const StepUniforms& u);
  // Sweeps from..to-1 of the step, in one parallel region.
  void runSweeps(const StepUniforms& u, int from, int to);
  // Stage coarse_correction: the patch system assembled, solved and applied (coarse_correction.h).
  void correctCoarsely(const StepUniforms& u);
  // Stage energy_budget: every particle's share of the step's energy, summed in the fixed tree order, and for a
  // closed film the gas's energy change between the volumes before and after.
  VelocityBudget budgetEnergy(const StepUniforms& u);
  // Stage external_drift: every particle's externalDrift summed in the fixed tree order, the film's drift.
  Vec3 filmDrift();
  // The tree sum (treeSum) of the triangles' volumes (triangleVolumes, at the step's start with atStepStart), four
  // triangles at a time in parallel: the volume's reduction.
  float volumeOf(const Film& film, const Vec3& origin, bool atStepStart);
  // Boyle's pressure of a closed film at the last volume (Eq. 11), P_0 for an open film.
  [[nodiscard]] float currentPressure(const StepUniforms& u) const;
  template <class Body>
  void timed(Stage stage, Body&& body);

  [[nodiscard]] const Params& params() const { return *params_; }

  const Params* params_ = nullptr;  // the caller's, read at every stage (Stepper::load)
  Film* film_ = nullptr;
  std::vector<float> triangleVolumes_;    // scratch for the volume reduction, reused every step
  std::vector<float> flowLogSurfactant_;  // the film flow's ln Gamma of each particle (filmFlowLogSurfactant)
  std::vector<float> flowSwept_;          // the film flow's swept area of each spring from each end (filmFlowLimit)
  float lastVolume_ = 0.0f;               // result of the last Volume stage, read by Forces
  // The volume stage's result within step(): the volume at the step's start, which the energy budget of a film
  // without wire particles takes again (its positions at the step's start are the same x_t, to the same floats).
  std::optional<float> stepStartVolume_;
  bool stepping_ = false;  // within step(): the stages run in their order
  SweepRuns sweepRuns_;    // the implicit step's one-rings, laid out again every step
  CoarseSystem coarse_;    // the implicit step's patch system, assembled again every step
  HeldPieces heldPieces_;  // energy_budget's springs' or triangles' shares of E, before the particles gather them
  std::array<std::vector<float>, GB_ENERGY_TERMS> energyTerms_;  // energy_budget's per-particle terms (ParticleEnergy)
  std::array<std::vector<float>, kDriftTerms> driftTerms_;       // external_drift's per-particle terms (externalDrift)
  Vec3 drift_ = Vec3::Zero();  // a closed film's drift (external_drift), read by implicit_predict
};

}  // namespace gb
