#pragma once
// What a stepper whose film lives on a device (VulkanStepper, host/) offers besides the step (Stepper): bringing the
// state back into host memory, taking the changes the rules between steps made to the film, and running some of
// those rules and the film checks on the device itself. A stepper that steps the film in host memory has none of
// this: Stepper::device() is then null, and Simulation works on the film in place.

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

#include "model/film.h"
#include "model/params.h"
#include "topology/film_checks.h"

namespace gb {

struct ContactHistory;  // collision.h

// What a stepper has copied from its device into host memory since it was made: whole-state read-backs (store)
// and the bytes of every copy (the state, the contact list, the reductions' few floats).
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

// What a round of merges tries, found on the device (kernels/statistics/crowded_springs.comp): the median of the
// living springs' squared lengths (squaredLengthOf), exactly the CPU's, whose root is the CPU's median spring; and the
// living springs that the film checks' loosened tests (kFilmCheckMargin) find crowded and shorter than kCrowdedEdge
// of the median spring, ascending: every spring the CPU's tests pass (crowdedSpringsAmong, keepTheMergeable), and
// perhaps a few more that they then drop.
struct CrowdedCandidates {
  float medianSquaredLength = 0.0f;
  std::vector<uint32_t> springs;
};

class DeviceResidency {
 public:
  virtual ~DeviceResidency() = default;

  // Brings the per-particle state back into the film given to Stepper::load.
  virtual void store(Film& film) = 0;
  // Brings back only the particles' positions (a renderer drawing the stepper's buffers in place frames the film
  // from them).
  virtual void storePositions(Film& film) = 0;
  // Brings back the per-particle arrays of film.state listed (by address) for every particle: what a rule between
  // steps reads of the whole film (the merges choose by the positions, thickness and elasticity).
  virtual void storeParticleArrays(Film& film, std::initializer_list<const void*> arrays) = 0;
  // Brings back a region of the film where a rule between steps reads it, not the whole state: the per-particle state
  // store() brings back, of the particles listed, and the rest lengths of the springs listed (both ascending). False
  // where the stepper brings back nothing by regions (the caller then calls store()).
  virtual bool storeRegion(Film& film, std::span<const uint32_t> particles, std::span<const uint32_t> springs) = 0;
  // Brings back the per-particle arrays of film.state listed (by address) of the particles listed (ascending), and
  // the rest lengths of the springs listed (ascending): what the burst's front reads (particlesTheFrontReads), or a
  // round of merges. False where the stepper brings back nothing by regions.
  virtual bool storeParticleArraysOf(Film& film, std::span<const uint32_t> particles,
                                     std::initializer_list<const void*> arrays, std::span<const uint32_t> springs) = 0;
  // Finds on the device what a round of merges tries (mergeCrowdedParticles, CrowdedCandidates above), from the state
  // as the last step or update left it. False where the caller finds it in host memory.
  virtual bool findCrowdedSprings(CrowdedCandidates& found) = 0;
  // Takes a film whose merges (makeMerges) changed the particles listed (ascending) and renumbered its springs: those
  // particles' per-particle arrays, the mesh's connectivity, and the rest lengths, each spring k keeping the one the
  // device holds for spring from[k] of the mesh before, or taking the film's where from[k] is kMadeSpring. The
  // geometry stays as the step left it (another round of merges reads the thickness the CPU's merges read) until
  // refreshGeometry. False where the stepper takes only whole films.
  virtual bool updateMergedRegion(const Params& params, Film& film, std::span<const uint32_t> particles,
                                  std::span<const uint32_t> from) = 0;
  // Brings the geometry and film state on the device up to the present positions, as a load leaves them.
  virtual void refreshGeometry() = 0;
  // Takes a film that a rule between steps changed in a region and may have grown (film growth at the wire appends
  // particles, springs and triangles, old indices staying): the per-particle arrays of the particles listed and of
  // those from firstNewParticle on, the rest lengths of the springs listed and of those from firstNewSpring on, and the
  // mesh's connectivity. Everything else the stepper holds stays, its state included, and its contact list stays the
  // history of the next search. False where the stepper takes only whole films (the caller then calls Stepper::load).
  virtual bool updateRegion(const Params& params, Film& film, std::span<const uint32_t> particles,
                            size_t firstNewParticle, std::span<const uint32_t> springs, size_t firstNewSpring) = 0;
  // Takes a film whose mesh shrank but whose particles did not move or change (a burst removed springs and
  // triangles and flagged particles dead): writes only the topology, its rest lengths and the alive flags, and keeps
  // the state and the contact list (the next search's history) on the device. False where the mesh does not fit the
  // loaded one's room: the caller then brings the state back and loads the film (Stepper::load).
  virtual bool updateTopology(const Params& params, Film& film) = 0;
  // Takes the film's changed spring rest lengths (the wire paying out film between frames, film_growth.h).
  virtual void updateRestLengths(const Film& film) = 0;
  // Takes the film's new self-collision contact list (Topology::contacts), found between frames.
  virtual void updateContacts(const Film& film) = 0;
  // Finds the film's self-collision contacts for the next frame itself, the list findContacts makes with the same
  // arguments (collision.h), and leaves it in film.topology.contacts too. Returns false when the stepper leaves the
  // search to the caller (findContacts on the CPU, then updateContacts).
  virtual bool findContacts(const Params& params, float frameTime, float slack, Film& film,
                            const ContactHistory& history) = 0;
  // Finds the contacts as findContacts does but leaves the list on the device, for the sweeps (storeContacts brings
  // it into film.topology.contacts when the CPU needs it); the list's entries are counted in host memory. False when
  // the stepper leaves the search to the caller.
  virtual bool findContactsOnDevice(const Params& params, float frameTime, float slack,
                                    const ContactHistory& history) = 0;
  virtual void storeContacts(Film& film) = 0;
  // Sums and checks the film on the device (FilmSums, and FilmChecks of film_checks.h with its thresholds loosened by
  // kFilmCheckMargin), the cone volumes to probe.origin, and reads back a few floats. With probe.atPresentPositions
  // the geometry and film state are first brought up to the present positions, as the statistics want; without, the
  // checks see them as the last step left them, as the rules between steps read them. Returns false when the caller
  // sums and checks the film in host memory.
  virtual bool probeFilm(const FilmProbe& probe, FilmSums& sums, FilmChecks& checks) = 0;
  // Runs a rest-length rule between steps on the rest lengths on the device, from the state as the last step left it:
  // the yield of stretched springs, or the wire's payout (yieldStretchedSprings and payOutFilmAtWire of
  // film_growth.h, with the same tests). They change there, and storeRestLengths brings them into
  // film.topology.restLength. False when the caller runs the rule on the film in host memory (and uploads the rest
  // lengths with updateRestLengths).
  virtual bool yieldStretchedSprings() = 0;
  virtual bool payOutFilmAtWire() = 0;
  // The same for the contraction of a closed film's slack springs (contractSlackSprings), each `share` of the way
  // (contractionShareOf: the caller weighs the checks' contractionEnergy against the allowance).
  virtual bool contractSlackSprings(float share) = 0;
  virtual void storeRestLengths(Film& film) = 0;
  // What has been copied into host memory so far (Simulation::readbackRecord).
  [[nodiscard]] virtual DeviceReadback readback() const = 0;
};

}  // namespace gb
