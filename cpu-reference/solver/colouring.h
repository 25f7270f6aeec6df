#pragma once
// Graph colouring for the implicit solver's Gauss-Seidel sweeps (a coloured sweep is order-free: no two
// particles of a colour share a spring). Made on the CPU when a film is loaded with a new mesh and handed to both
// backends, so that they solve the same particles in the same colour order. Contacts need none (the solver reads a
// contact partner where inertia carries it, implicit_euler.cpp); buildAdjacency drops it whenever the springs change.

#include "model/state.h"

namespace gb {

// A particle the implicit solver moves: living and not held by the wire.
bool isSolverParticle(const std::vector<uint32_t>& alive, const Topology& topo, size_t i);

// Greedy colouring in particle order: each living interior particle takes the smallest colour that none of
// its spring neighbours has. Boundary (wire) and dead particles are not moved by the solver and
// get no colour. Fills topo.colourOffset and topo.colourOrder (particles of a colour in increasing index).
void colourParticles(const std::vector<uint32_t>& alive, Topology& topo);

// Colours the film's particles unless its topology already has a colouring.
void ensureColouring(const std::vector<uint32_t>& alive, Topology& topo);

// True when no spring joins two particles of the same colour and every living interior
// particle has exactly one colour (tests, and a guard before a solve).
bool isValidColouring(const std::vector<uint32_t>& alive, const Topology& topo);

}  // namespace gb
