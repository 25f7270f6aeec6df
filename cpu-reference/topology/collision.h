#pragma once
// Self-collision of the film (Section 8). Between frames, a uniform hash grid finds the pairs of particles
// that may touch during the next frame; the forces stage of both backends then repels the pairs closer
// than Params::collisionDistance (a gather over each particle's contact list, pair forces equal and
// opposite, tangential motion free so that the sheets slip). A contact hit too hard bursts the film there
// (lambda_col, findImpact).

#include <memory>

#include "kernels/shared/shared_formulas.h"
#include "model/film.h"

namespace gb {

// The contact list the last search left (Topology::contacts) and the particle count it was made for. Particles
// keep their indices while the film grows at the wire, pinches off and bursts (new ones are appended, dead ones
// stay), so a pair still listed keeps its rest distance; a new dip starts an empty history.
struct ContactHistory {
  std::vector<uint32_t> contacts;
  size_t particles = 0;
  bool onDevice = false;  // the list is the one the stepper's last search left on its device (contacts is empty)
};

// A listed pair's rest distance: the collision distance, or the pair's separation when it enters the list
// already closer. A pair then brings no penalty energy with it: pushed out to the full distance at once, the
// overlaps a new list admits (a crumpled film's own wrinkles folding across the 45-degree test, sheets that
// closed faster than the search's margin) made energy from nothing, 0.3-0.45 J a frame in the 25,650-particle
// stress run (docs/performance.md). It grows back as the pair separates and never shrinks while the pair stays
// listed, so a new list never raises the penalty energy and the step's own approach is resisted as before. The
// formula is kernels/shared/shared_formulas.h's, which the device search (host/vulkan_stepper.h) shares.
float contactRestDistanceAfter(const Params& params, float previousRest, float separation);

// Fills film.topology.contacts: for every living particle, the living particles that may come within
// collisionDistance of it during the next frame of frameTime and that are not its one-ring neighbours and lie
// across the film from it (their separation makes an angle under 45 degrees with one of the two normals, so
// neighbours along the same sheet are left out), each pair with its rest distance (contactRestDistanceAfter, with
// the rest distance it had in `history`). A pair may close by h |v_i - v_j| at its start
// velocities, plus slack for what the frame's forces add; the margin is capped at kMaxContactMargin. The list is
// symmetric and sorted. Returns the number of pairs. The margin (contactMargin, kMaxContactMargin) and the across test
// (liesAcross) are kernels/shared/shared_formulas.h's, shared with the device search
// (kernels/contacts/contact_pairs.comp).
size_t findContacts(const Params& params, float frameTime, float slack, Film& film, const ContactHistory& history = {});

// findContacts with the memory it keeps from one search to the next: a film of a million particles has a cell
// table and per-particle lists of tens of megabytes, which a search of its own allocates and zeroes each time
// (about 30 ms of a 370 ms frame at 1,000,000 particles, docs/performance.md). The lists found are the same. A copy
// starts with no memory.
class ContactSearch {
 public:
  ContactSearch();
  ~ContactSearch();
  ContactSearch(const ContactSearch&);
  ContactSearch& operator=(const ContactSearch&);
  size_t find(const Params& params, float frameTime, float slack, Film& film, const ContactHistory& history = {});

 private:
  struct Memory;
  std::unique_ptr<Memory> memory_;
};

// The impact of two film particles meeting at approach speed v (the closing speed along their separation):
// the film Weber number m_A v^2 / E, the dynamic pressure of the approach over the film's tension, with m_A
// the film's inertia per area (Params::filmInertia) and E the mean elasticity of the two (N/m, the tension
// scale of Eq. 4). Dimensionless, like the paper's lambda_col in [1.5, 2]: the film bursts above it.
float impactNumber(const Params& params, float approachSpeed, float elasticity);

// The living particle nearest to x and its distance (infinite when none lives): a linear scan, for the two
// wand tips.
struct Nearest {
  size_t particle = 0;
  float distance = 0.0f;
};
Nearest nearestParticle(const State& state, const Vec3& x);

// Generalised winding number of a closed film around x: the sum of its triangles' signed solid angles over
// 4 pi (Van Oosterom and Strackee 1983). 1 inside a bubble with outward normals, 0 outside, robust to folds.
double windingNumber(const Film& film, const Vec3& x);

// Whether x lies inside a closed film: its winding number is over 1/2. Outside the box of the film's living
// particles a closed surface winds 0 times around a point, so the sum over every triangle (a millisecond on the
// default bubble, each frame for each wand) is taken only inside it.
bool insideClosedFilm(const Film& film, const Vec3& x);

struct Impact {
  size_t particle = 0;  // the faster particle of the hardest pair
  float number = 0.0f;  // its impact number; 0 when no pair is in contact and closing
};

// The hardest impact the next frame will see: among the contact pairs, those closing at their current speed
// to within Params::collisionDistance in frameTime (a fast sheet crosses the contact zone within a frame,
// so an impact is judged before the frame, not after).
Impact hardestImpact(const Params& params, float frameTime, const Film& film);

}  // namespace gb
