#include "stepper.h"

#include <array>

namespace gb {

namespace {

bool always(const Params&, const StepUniforms&) { return true; }
bool closedFilm(const Params&, const StepUniforms& u) { return u.closed != 0; }
bool explicitStep(const Params& p, const StepUniforms&) { return p.integrator == 0; }
bool implicitStep(const Params& p, const StepUniforms&) { return p.integrator != 0; }
bool closedImplicitStep(const Params& p, const StepUniforms& u) { return p.integrator != 0 && u.closed != 0; }
bool budgetedStep(const Params& p, const StepUniforms&) { return p.integrator != 0 && p.energyBudget != 0; }
// The coarse correction runs inside vertex_block_descent, between its smoothing sweeps (coarse_correction.h),
// never as a row of its own.
bool insideTheSweeps(const Params&, const StepUniforms&) { return false; }
bool drainsThisStep(const Params&, const StepUniforms& u) { return u.drainageDt > 0; }

constexpr std::array kStages = {
    StageSpec{Stage::Geometry, "geometry", always, "film state, air and forces gather the areas and normals"},
    StageSpec{Stage::Volume, "volume", closedFilm, "the forces read the enclosed volume (Boyle's law)"},
    StageSpec{Stage::FilmState, "film_state", always, nullptr},  // read first by the forces, after a barrier
    StageSpec{Stage::AirInflow, "air_inflow", always, "the air transfer hands the inflow to the end particles"},
    StageSpec{Stage::AirTransfer, "air_transfer", always, "the forces read the transferred air"},
    StageSpec{Stage::Forces, "forces", explicitStep, "integration must not move particles the forces still read"},
    StageSpec{Stage::Integrate, "integrate", explicitStep, "drainage and the next step read the new positions"},
    StageSpec{Stage::ExternalForces, "external_forces", implicitStep,
              "the prediction must not move particles whose normals the forces still read"},
    StageSpec{Stage::ExternalDrift, "external_drift", closedImplicitStep, "the prediction reads the film's drift"},
    StageSpec{Stage::ImplicitPredict, "implicit_predict", implicitStep,
              "the solver reads x_t, the placed wire and the first guess"},
    StageSpec{Stage::VertexBlockDescent, "vertex_block_descent", implicitStep,
              "the energy budget and the velocity read the solved positions"},
    StageSpec{Stage::CoarseCorrection, "coarse_correction", insideTheSweeps, nullptr},
    StageSpec{Stage::EnergyBudget, "energy_budget", budgetedStep, "the velocity reads the budget's factor"},
    StageSpec{Stage::ImplicitVelocity, "implicit_velocity", implicitStep,
              "drainage and the next step read the new positions and velocities"},
    StageSpec{Stage::Drainage, "drainage", drainsThisStep, "the next step's film state reads the new liquid"},
};
static_assert(kStages.size() == kStageCount, "every stage has one row");

}  // namespace

std::span<const StageSpec> stepStages() { return kStages; }

const char* stageName(Stage stage) {
  for (const StageSpec& spec : kStages)
    if (spec.stage == stage) return spec.name;
  return "unknown";
}

}  // namespace gb
