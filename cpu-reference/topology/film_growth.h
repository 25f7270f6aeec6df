#pragma once
// Film growth and soap solution control (Section 7, Figure 14c-d). A wet wire keeps drawing new film while
// the wands stretch the film, in two steps:
//  1. Payout, every frame: a spring joining the wire to the film ("rung") stretched past
//     Params::growthStretch times its rest length gets the rest length of a new film at its current length
//     (prestrained): film has come out of the wire, and the band next to the wire widens instead of
//     stretching. Only rest lengths change, so a GPU stepper is patched, not reloaded.
//  2. Ring insertion, when the band's rungs rest at kRingInsertionWidth wire spacings: the wire lets go of its
//     ring of particles, which move halfway along the rungs into the film, and a new ring of particles takes
//     the wire; the strip between the two rings is triangulated by CGAL's Delaunay triangulation. The strip's
//     liquid (a new film's thickness) comes from the wire, whose solution runs out; the new ring's spacing
//     follows the remaining solution as a dip with that much solution would (Figure 9): spacing ~
//     1 / sqrt(solution). A dry wire pays out no film.

#include <compare>
#include <cstdint>
#include <span>
#include <vector>

#include "model/film.h"

namespace gb {

// The wire draws film only while the wands move (Section 7): a film hanging still sags under its weight but
// does not grow. Wand tips slower than this (m/s) are still.
inline constexpr float kDrawingSpeed = 0.05f;

// Rungs this many wire spacings long at rest make room for a new ring: the two halves come out about 0.8
// spacing wide, no slivers.
inline constexpr float kRingInsertionWidth = 1.6f;

// Mean length / rest length of the rungs; 0 when there is none (a closed bubble, a film without wire).
float wireRungStretch(const Film& film);

// Mean rest length of the rungs in units of the mean spacing of the wire's particles.
float wireBandWidth(const Film& film);
// The same from the rungs' count and summed rest length and the wire's springs' count and summed length (0 when a
// count is 0).
float wireBandWidthOf(double rungRest, double rungs, double edgeLength, double edges);

// Step 1 alone: lengthens the rest of every rung stretched past Params::growthStretch, if the film is open
// and intact and the wire still holds liquid. Returns how many rungs it lengthened.
size_t payOutFilmAtWire(const Params& params, Film& film);

// Plastic yield of the film itself: every spring stretched past Params::yieldStretch times its rest length
// gets a rest length that keeps it exactly at the yield stretch. A soap film is not rubber: stretched well
// past its elastic (Gibbs) range it makes new surface out of its own thickness rather than pulling harder, so a
// bag the air has drawn out sags when the air stops instead of springing back flat. The film's liquid stays
// with its particles, so a yielded region thins. Springs held by the wire pay out by the wire's rule instead, and
// the physical model (tensionModel 1) has no rest lengths to yield. Returns how many springs yielded (0 with
// yieldStretch 0, or below 1: off).
size_t yieldStretchedSprings(const Params& params, Film& film);

// The spring energy the rest-length rules of a frame may still add (J): VelocityBudget::released, the energy the step
// before released below its energy budget. Unbounded where no budget was kept.
struct SpringEnergyAllowance {
  float joules = std::numeric_limits<float>::infinity();
  // Takes `energy` from the allowance where it holds that much; a negative energy gives some back.
  bool pays(float energy) {
    if (energy > joules) return false;
    joules -= energy;
    return true;
  }
};

// A soap film cannot be compressed: where it is pushed together it contracts and thickens rather than
// wrinkling (its surface tension, 2 gamma, never falls to zero). Every spring shorter than its rest length (slack:
// no tension left) gets the rest length of a new film of its length, as taut as when it was made
// (Params::springPrestrain), unless one of its ends is already as thick as the film was dipped (a region that keeps
// being pushed together would otherwise gather into a lump tens of microns thick while the rest thins). The film's
// liquid stays with its particles, so a contracted region thickens. Springs
// held by the wire follow the wire's rule; the physical model has constant tension and no rest lengths. With
// Params::energyNeutralContraction a spring is stretched only by as much as it was compressed, so the rule adds no
// spring energy (docs/model.md "Energy budget"). Otherwise the springs it contracts put back no more spring energy
// than `allowance` holds, the energy the last step released below its energy budget (VelocityBudget::released): the
// film's tension stands in for a surface energy the springs do not hold, and it rounds the bubble no faster than
// the bubble's motion dissipates, so the film never gains energy from it. Where the allowance does not pay for all
// of them, every slack spring goes the share of the way that spends it exactly (contractionShareOf): a rule of each
// spring by itself once the share is known, which the Vulkan stepper runs on its device (film_rest_lengths.comp).
// Returns how many springs contracted.
size_t contractSlackSprings(const Params& params, Film& film, SpringEnergyAllowance& allowance);
size_t contractSlackSprings(const Params& params, Film& film);  // no bound
// The spring energy contractSlackSprings adds taking every slack spring the share s of the way, s^2 quadratic -
// s linear (J; contractionQuadraticOf and contractionLinearOf), summed in double in the springs' order.
struct ContractionEnergy {
  float quadratic = 0.0f, linear = 0.0f;
};
ContractionEnergy contractionEnergy(const Params& params, const Film& film);

// Where a closed film stays pushed together because it is too thick to contract (above), its particles merge:
// a spring between two particles of which one is at least as thick as the dip, shorter than its rest length and
// than kCrowdedEdge of the film's median spring, collapses into the pair's centre of mass (mass, liquid and
// momentum conserved; the second particle dies, keeping its index). The crumpled film that the pinch-off seam
// gathers otherwise stays folded in fine wrinkles for the bubble's whole flight. A merge is skipped where it would
// break the manifold (the two one-rings share other particles than the two across the edge) or turn a triangle
// over, and no two merges touch the same one-ring in one call. New springs rest as at creation
// (rebuildTopology). Returns how many particles merged; the caller refreshes the geometry and reloads the stepper.
// kCrowdedEdge (shared_formulas.h) is the fraction of the median spring.
// The springs a merge makes rest as taut as new film while `allowance` pays for their energy, at their length
// (no energy) after.
size_t mergeCrowdedParticles(const Params& params, Film& film, SpringEnergyAllowance& allowance);
size_t mergeCrowdedParticles(const Params& params, Film& film);  // no bound

// mergeCrowdedParticles in its parts, for a film whose state is on a device and comes back in regions
// (Simulation::mergeCrowdedParticlesWhereTheyLie): each part reads the film's state only where it says.
//
// A crowded spring (springCrowded) and its length.
struct CrowdedSpring {
  float length;
  size_t spring;
  auto operator<=>(const CrowdedSpring&) const = default;  // the shortest first; ties by spring: deterministic
};
// The length of the spring between particles a and b: the root of squaredLengthOf, as the device's median is taken.
float springLength(const State& s, uint32_t a, uint32_t b);
// The median of the living springs' lengths (both ends alive): reads every position.
float medianSpringLength(const Film& film);
// The living springs that are crowded, of all (reads every position and thickness and rest length), or of those
// listed (reads only theirs and their ends').
std::vector<CrowdedSpring> crowdedSprings(const Params& params, const Film& film);
std::vector<CrowdedSpring> crowdedSpringsAmong(const Params& params, const Film& film,
                                               std::span<const uint32_t> springs);
// Keeps those shorter than kCrowdedEdge of the median spring, shortest first: the springs a merge round tries.
void keepTheMergeable(std::vector<CrowdedSpring>& crowded, float medianLength);
// A merge: the particle that joins another, and the one it joins (which survives at their centre of mass).
struct Merge {
  uint32_t survivor, joining;
};
// The merges a round makes of the springs it tries, in that order: those that keep the mesh a manifold without
// folds, no two touching the same one-ring. Reads the positions of the springs' ends and their one-rings.
std::vector<Merge> chooseMerges(const Film& film, const std::vector<CrowdedSpring>& tried);
// Makes the merges and collapses the mesh; `from`, if given, gets where each spring of the new mesh comes from
// (collapsedTopology). Reads and writes the whole state of the merged particles, and reads the positions, thickness
// and elasticity of their one-rings.
void makeMerges(const Params& params, Film& film, const std::vector<Merge>& merges, SpringEnergyAllowance& allowance,
                std::vector<uint32_t>* from = nullptr);

struct GrowthEvent {
  size_t restLengthsChanged = 0;  // rungs lengthened by the payout
  size_t particlesAdded = 0;      // the new ring (0: no ring inserted)
  size_t trianglesAdded = 0;
  float liquidUsed = 0.0f;  // m^3 taken from the wire
};

// Both steps on an open, intact film (one boundary loop) at the wire frame `frame` of now, the payout only
// while the faster wand tip moves at wandSpeed >= kDrawingSpeed; a closed, torn or dry film is left as it is. New
// particles are appended (old indices stay); the mesh stays an oriented manifold disc whose boundary is the new ring.
// With payOut false the payout has been done elsewhere (on the stepper's device): only a new ring is looked for.
GrowthEvent growFilmAtWire(const Params& params, const WireFrame& frame, float wandSpeed, Film& film,
                           bool payOut = true);

// Whether the film is open and intact, with one boundary loop on its wire: where the wire pays out film.
bool wireLoopIntact(const Film& film);

// A region of a film: particles and springs, each ascending.
struct FilmRegion {
  std::vector<uint32_t> particles, springs;
};
// What growFilmAtWire reads of a film's per-particle state and rest lengths, and all it changes of the particles and
// springs the film had: the wire's particles and the two rings of film inside them (the wire's ring moves along its
// rungs, the film joined to it takes new geometry and liquid, and its triangles reach one ring further), and the
// springs of the wire's particles (the rungs, whose rest lengths measure the band and are made anew). A film whose
// state lies on a device brings back this much for a ring at the wire (Stepper::storeRegion).
FilmRegion wireGrowthRegion(const Film& film);

}  // namespace gb
