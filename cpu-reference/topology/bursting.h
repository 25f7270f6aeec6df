#pragma once
// Soap film bursting (Section 6.1, Algorithm 3) and its aerosol. Topology events run on the CPU between
// frames; the stepper is then given the changed film.
//
// A particle thinner than the thickness threshold starts a crack. The hole front then spreads over the
// mesh: in Taylor-Culick mode (default) it reaches neighbour j of a burst particle i at
// t_j = t_i + |x_j - x_i| / sqrt(2 gamma / (rho e_j)), a shortest-path (Dijkstra) front measured in metres
// and seconds, so a burst takes the same time whatever the substep and the mesh resolution; in the paper's
// mode it advances one ring of neighbours per frame. A particle the front reaches dies (flagged, never
// renumbered); its springs go, and so does every triangle that touched it. Triangles whose three particles
// are all dead become aerosol droplets carrying their liquid, gathered a few centimetres at a time
// (bursting.cpp, emitDroplets).

#include <cstdint>
#include <limits>
#include <vector>

#include "model/film.h"

namespace gb {

// Aerosol droplets (structure of arrays). They fly ballistically with gravity and linear air drag, and
// fade out after Params::aerosolLifetime or when they reach the floor (y = 0).
struct Aerosol {
  Vec3Array position;
  Vec3Array velocity;
  std::vector<float> mass;  // kg of liquid (the film's liquid volume times its density)
  std::vector<float> age;   // s

  [[nodiscard]] size_t size() const { return mass.size(); }
  void add(const Vec3& x, const Vec3& v, float m);
  void advance(const Params& params, float dt);
};

// Bursting bookkeeping of a film, kept by the simulation beside it.
struct BurstFront {
  std::vector<float> arrival;    // time the hole reaches each particle (s), +inf when not yet known
  std::vector<uint32_t> shares;  // triangles each particle had when the burst began: its mass splits
                                 // evenly into that many droplets
  std::vector<uint32_t> torn;    // triangles left the physics mesh with a dead corner, 3 indices each
  double started = -1.0;         // time of the first crack, -1 before
  double finished = -1.0;        // time the last particle died, -1 before
  const char* cause = nullptr;   // what scheduled the first crack: "thin", "impact", "wand", "floor" or "poke"
  [[nodiscard]] bool active() const { return started >= 0 && finished < 0; }
};

// What one frame's topology events did.
struct TopologyEvents {
  bool started = false;         // the first crack of this film opened
  const char* cause = nullptr;  // with started: BurstFront::cause
  bool finished = false;        // the film is gone
  size_t particlesRemoved = 0;
  size_t trianglesRemoved = 0;  // left the physics mesh
  size_t dropletsEmitted = 0;
  double dropletMassEmitted = 0.0;  // kg those droplets carry: the aerosol fades, this keeps the film's account
  bool pinchedOff = false;          // the film closed into a free bubble this frame (pinch_off.h)
  size_t particlesAdded = 0;        // new film drawn off the wire this frame (film_growth.h)
};

// Taylor-Culick speed of a hole's rim in a film of thickness e: sqrt(2 gamma / (rho e)) (m/s).
float taylorCulickSpeed(const Params& params, float thickness);

// Schedules a crack at particle i at time t; cause says why (a poke, a collision, the thickness test...); the
// burst keeps the first one's.
void startCrack(BurstFront& front, const Film& film, size_t i, double t, const char* cause);

// One frame's topology step at time `now`: cracks where the film is thinner than the threshold (crackWhereThin),
// then the front advanced to `now`, the particles it reached removed with their springs and triangles, droplets
// emitted for triangles with no living corner, and the CSR one-ring rebuilt (advanceFront). Returns what happened;
// the film's topology changed iff particlesRemoved > 0.
TopologyEvents advanceBurst(const Params& params, double now, Film& film, BurstFront& front, Aerosol& aerosol);
void crackWhereThin(const Params& params, double now, const Film& film, BurstFront& front);
TopologyEvents advanceFront(const Params& params, double now, Film& film, BurstFront& front, Aerosol& aerosol);

// What advanceFront reads of the particles' state, beyond those `readable` flags (one flag a particle): the
// particles the front reaches and their neighbours (their positions and thickness), and the corners of the triangles
// that die (their positions, velocities, liquid and thickness, for the droplets). Ascending; empty when the readable
// particles are all the front reads. Where the state lies on a device, the front brings back only these: asked again
// with them readable until it names none, since a front that reads further may reach further (Simulation).
std::vector<uint32_t> particlesTheFrontReads(const Params& params, double now, const Film& film,
                                             const BurstFront& front, const std::vector<char>& readable);

}  // namespace gb
