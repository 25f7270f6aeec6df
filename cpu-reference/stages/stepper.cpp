#include "stages/stepper.h"

#include <array>

namespace gb {

namespace {

bool always(const Params&, const StepUniforms&) { return true; }
bool closedFilm(const Params&, const StepUniforms& u) { return u.closed != 0; }
bool explicitStep(const Params& p, const StepUniforms&) { return p.integrator == 0; }
bool implicitStep(const Params& p, const StepUniforms&) { return p.integrator != 0; }
bool closedImplicitStep(const Params& p, const StepUniforms& u) { return p.integrator != 0 && u.closed != 0; }
bool budgetedStep(const Params& p, const StepUniforms&) { return p.integrator != 0 && p.energyBudget != 0; }
// The coarse correction has a row, for the tests and benchmarks that run it alone (runStage), but a step runs it
// inside vertex_block_descent, between its smoothing sweeps (coarse_correction.h): its row never runs by itself.
bool insideTheSweeps(const Params&, const StepUniforms&) { return false; }
bool drainsThisStep(const Params& p, const StepUniforms& u) { return u.drainageDt > 0 && p.filmFlow == 0; }
bool flowsThisStep(const Params& p, const StepUniforms& u) { return u.drainageDt > 0 && p.filmFlow != 0; }

using enum gpu::Binding;
// What the gathers read of the mesh: a particle's springs, and its triangles by corner.
constexpr uint32_t kSprings =
    bufferSet({GB_BINDING_SPRING_OFFSET, GB_BINDING_SPRING_INDEX, GB_BINDING_SPRING_NEIGHBOUR, GB_BINDING_REST_LENGTH});
constexpr uint32_t kTriangleRing =
    bufferSet({GB_BINDING_TRIANGLES, GB_BINDING_TRIANGLE_OFFSET, GB_BINDING_TRIANGLE_CORNER});
// What the forces of a particle read (forces.glsl's internalForce and externalForce).
constexpr uint32_t kForceInputs =
    kSprings | kTriangleRing |
    bufferSet({GB_BINDING_POSITION, GB_BINDING_VELOCITY, GB_BINDING_ELASTICITY, GB_BINDING_TRIANGLE_NORMAL,
               GB_BINDING_CONTACTS, GB_BINDING_REDUCE, GB_BINDING_LIQUID, GB_BINDING_NORMAL, GB_BINDING_VORONOI_AREA,
               GB_BINDING_AIR_FLOW, GB_BINDING_AIR_INFLOW});
// What a particle's block of the implicit objective reads (vertex_block.glsl's objectiveBlock).
constexpr uint32_t kObjectiveInputs =
    kForceInputs | bufferSet({GB_BINDING_COLOUR_ORDER, GB_BINDING_ALIVE, GB_BINDING_MASS, GB_BINDING_PREVIOUS_POSITION,
                              GB_BINDING_FORCE, GB_BINDING_BOUNDARY});

constexpr std::array kStages = {
    StageSpec{
        Stage::Geometry, "geometry", always, kTriangleRing | bufferSet({GB_BINDING_POSITION}),
        bufferSet({GB_BINDING_TRIANGLE_NORMAL, GB_BINDING_CORNER_AREA, GB_BINDING_NORMAL, GB_BINDING_VORONOI_AREA}),
        "film state, air and forces gather the areas and normals"},
    StageSpec{Stage::Volume, "volume", closedFilm,
              bufferSet({GB_BINDING_POSITION, GB_BINDING_TRIANGLES, GB_BINDING_REDUCE}), bufferSet({GB_BINDING_REDUCE}),
              "the forces read the enclosed volume (Boyle's law)"},
    StageSpec{Stage::FilmState, "film_state", always,
              bufferSet({GB_BINDING_VORONOI_AREA, GB_BINDING_LIQUID, GB_BINDING_MASS, GB_BINDING_LIFETIME}),
              bufferSet({GB_BINDING_THICKNESS, GB_BINDING_ELASTICITY, GB_BINDING_LIFETIME}),
              nullptr},  // read first by the forces, after air_inflow's barrier
    StageSpec{Stage::AirInflow, "air_inflow", always, bufferSet({GB_BINDING_POSITION}),
              bufferSet({GB_BINDING_AIR_INFLOW}), "the air transfer hands the inflow to the end particles"},
    // Writes the back buffer, which the Jacobi swap makes the front (AIR_FLOW) for the stages after it.
    StageSpec{Stage::AirTransfer, "air_transfer", always,
              bufferSet({GB_BINDING_BOUNDARY, GB_BINDING_AIR_INFLOW, GB_BINDING_POSITION, GB_BINDING_SPRING_OFFSET,
                         GB_BINDING_SPRING_NEIGHBOUR, GB_BINDING_AIR_FLOW}),
              bufferSet({GB_BINDING_AIR_FLOW_NEXT, GB_BINDING_AIR_FLOW}), "the forces read the transferred air"},
    StageSpec{Stage::Forces, "forces", explicitStep, kForceInputs, bufferSet({GB_BINDING_FORCE}),
              "integration must not move particles the forces still read"},
    StageSpec{Stage::Integrate, "integrate", explicitStep,
              bufferSet({GB_BINDING_ALIVE, GB_BINDING_POSITION, GB_BINDING_BOUNDARY, GB_BINDING_WIRE_PARAM,
                         GB_BINDING_VELOCITY, GB_BINDING_FORCE, GB_BINDING_MASS}),
              bufferSet({GB_BINDING_VELOCITY, GB_BINDING_POSITION}),
              "drainage and the next step read the new positions"},
    StageSpec{Stage::ExternalForces, "external_forces", implicitStep,
              bufferSet({GB_BINDING_NORMAL, GB_BINDING_VORONOI_AREA, GB_BINDING_LIQUID, GB_BINDING_AIR_FLOW,
                         GB_BINDING_AIR_INFLOW, GB_BINDING_REDUCE}),
              bufferSet({GB_BINDING_FORCE}),
              "the prediction must not move particles whose normals the forces still read"},
    StageSpec{Stage::ExternalDrift, "external_drift", closedImplicitStep,
              bufferSet({GB_BINDING_ALIVE, GB_BINDING_BOUNDARY, GB_BINDING_FORCE, GB_BINDING_MASS, GB_BINDING_REDUCE}),
              bufferSet({GB_BINDING_REDUCE}), "the prediction reads the film's drift"},
    StageSpec{Stage::ImplicitPredict, "implicit_predict", implicitStep,
              bufferSet({GB_BINDING_REDUCE, GB_BINDING_ALIVE, GB_BINDING_POSITION, GB_BINDING_BOUNDARY,
                         GB_BINDING_WIRE_PARAM, GB_BINDING_VELOCITY}),
              bufferSet({GB_BINDING_PREVIOUS_POSITION, GB_BINDING_POSITION}),
              "the solver reads x_t, the placed wire and the first guess"},
    StageSpec{Stage::VertexBlockDescent, "vertex_block_descent", implicitStep, kObjectiveInputs,
              bufferSet({GB_BINDING_POSITION, GB_BINDING_REDUCE}),
              "the energy budget and the velocity read the solved positions"},
    StageSpec{Stage::CoarseCorrection, "coarse_correction", insideTheSweeps, kObjectiveInputs,
              bufferSet({GB_BINDING_POSITION, GB_BINDING_REDUCE}), nullptr},
    StageSpec{Stage::EnergyBudget, "energy_budget", budgetedStep,
              kSprings | kTriangleRing |
                  bufferSet({GB_BINDING_ALIVE, GB_BINDING_BOUNDARY, GB_BINDING_MASS, GB_BINDING_VELOCITY,
                             GB_BINDING_POSITION, GB_BINDING_PREVIOUS_POSITION, GB_BINDING_FORCE, GB_BINDING_ELASTICITY,
                             GB_BINDING_CONTACTS, GB_BINDING_REDUCE}),
              bufferSet({GB_BINDING_REDUCE}), "the velocity reads the budget's factor"},
    StageSpec{Stage::ImplicitVelocity, "implicit_velocity", implicitStep,
              bufferSet({GB_BINDING_ALIVE, GB_BINDING_POSITION, GB_BINDING_PREVIOUS_POSITION, GB_BINDING_BOUNDARY,
                         GB_BINDING_REDUCE}),
              bufferSet({GB_BINDING_VELOCITY}), "drainage and the next step read the new positions and velocities"},
    StageSpec{Stage::Drainage, "drainage", drainsThisStep,
              bufferSet({GB_BINDING_POSITION, GB_BINDING_SPRING_OFFSET, GB_BINDING_SPRING_NEIGHBOUR, GB_BINDING_LIQUID,
                         GB_BINDING_DRAINAGE}),
              bufferSet({GB_BINDING_DRAINAGE, GB_BINDING_LIQUID}), "the next step's film state reads the new liquid"},
    StageSpec{
        Stage::FilmFlow, "film_flow", flowsThisStep,
        bufferSet({GB_BINDING_ALIVE, GB_BINDING_BOUNDARY, GB_BINDING_POSITION, GB_BINDING_VELOCITY, GB_BINDING_NORMAL,
                   GB_BINDING_VORONOI_AREA, GB_BINDING_THICKNESS, GB_BINDING_LIQUID, GB_BINDING_AIR_FLOW,
                   GB_BINDING_SPRING_OFFSET, GB_BINDING_SPRING_NEIGHBOUR, GB_BINDING_DRAINAGE}),
        bufferSet({GB_BINDING_DRAINAGE, GB_BINDING_LIQUID}), "the next step's film state reads the new liquid"},
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
