#pragma once
// A film: its particles, its mesh and the facts about it that outlive a step.

#include "model/params.h"
#include "model/state.h"
#include "model/wire_frame.h"

namespace gb {

struct Film {
  State state;
  Topology topology;
  WandTool tool;
  float stringLength = 0.0f;         // two wands: length of the hanging bottom string, fixed while the film lives
  Vec3 loopHang = Vec3::Zero();      // two wands: the way the loop hangs now (its frame's `down`, see swingLoop);
                                     // zero: straight towards gravity
  float referenceVolume = 0.0f;      // V_0 of Eq. (11) once the film is a closed bubble (m^3)
  uint64_t geometryKey = 0;          // geometryKey (stages.h) of the geometry the CPU stepper computed last
  Vec3 volumeOrigin = Vec3::Zero();  // closed bubble: apex of the volume's cone decomposition, fixed at
                                     // closure so that no backend needs to read the state back for it
  // Soap solution control (Section 7): liquid still on the wet wire, from which new film is drawn.
  float wireLiquid = 0.0f;       // m^3 left
  float wireLiquidAtDip = 0.0f;  // m^3 the wire held when the film was made
  float wireSpacing = 0.0f;      // spacing of the wire's particles when the film was made (m)
  // Remaining soap solution in [0, 1]: Params::solution at the dip, less what growth has used since.
  [[nodiscard]] float solutionLeft(const Params& params) const {
    return wireLiquidAtDip > 0 ? params.solution * wireLiquid / wireLiquidAtDip : 0.0f;
  }
};

// Gives every particle its material at creation: geometry, then mass (film inertia x rest Voronoi area),
// liquid (initial thickness x rest Voronoi area), thickness, elasticity; lifetime 0, at rest.
void initialiseFilmMaterial(const Params& params, Film& film);

// The mass gravity pulls on: the particle's liquid. Air inside and outside the film weigh the same, so a
// film (and a free bubble) sinks under its liquid's weight alone.
inline float liquidMass(const Params& p, float liquid) { return p.liquidDensity * liquid; }

// The mass of a particle with that Voronoi area and liquid, its inertia: the paper's film has a chosen inertia
// per area (filmInertia, 0.1 kg/m^2, about 30 times a 3.5 um film's liquid); we read the difference as the air
// the film drags along (added mass), which it must accelerate but which weighs nothing in air, so gravity
// pulls on liquidMass only (docs/model.md, "The film"). The physical model (tensionModel 1) is its
// liquid alone.
inline float particleMass(const Params& p, float voronoiArea, float liquid) {
  return p.tensionModel == 1 ? liquidMass(p, liquid) : p.filmInertia * voronoiArea;
}

// Physical model: the liquid the particle was made with, which its mass still weighs (particleMass): drainage moves
// liquid between particles, never mass. The surfactant stays on the surface the particle was made with, so its
// surfactant per area, which the Gibbs law reads (filmTension), is this liquid over the particle's area, not the
// liquid it holds now: a film that drains thins without pulling harder.
inline float surfactantLiquid(const Params& p, float mass) { return mass / p.liquidDensity; }

// Gives particles [first, n) the material of a new film (mass, liquid, thickness, elasticity, at rest) from the
// Voronoi areas the state holds: the caller has updated the geometry around them.
void giveNewFilmMaterial(const Params& params, State& s, size_t first);
// The same after updating the geometry of the whole film: new particles stitched to an existing film.
void initialiseNewParticles(const Params& params, Film& film, size_t first);

// A film spanning the tool's wire frame (Sections 3 and 7): round(solution x particlesAtFullSolution)
// particles, boundary particles spaced evenly along the frame, interior particles on a hexagonal lattice,
// joined by a constrained Delaunay triangulation (CGAL) whose edges become springs. With less solution the
// two-wand loop is wetted less deep, so the film is smaller and rounder (Figure 9).
Film generateFilm(const Params& params, const WandTool& tool, const WandState& wands);

// A film spanning two coaxial rings of the given radius, `separation` apart along z around `center` (the
// catenoid experiment): `around` particles per ring, rows about as far apart as neighbours on a ring. The
// rings are pinned (wireParam -1); normals point away from the axis.
Film generateTube(const Params& params, const Vec3& center, float radius, float separation, int around);

// A closed spherical film (an icosphere with outward normals): a free bubble for tests and pressure scenes.
Film generateSphere(const Params& params, const Vec3& center, float radius, int subdivisions);

}  // namespace gb
