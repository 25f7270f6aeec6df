#pragma once
// Graph colouring for the implicit solver's Gauss-Seidel sweeps (ARCHITECTURE.md: a coloured sweep is
// order-free). Made on the CPU whenever the mesh or the contact list changes and handed to both backends,
// so that they solve the same particles in the same colour order.

#include "state.h"

namespace gb {

// Greedy colouring in particle order: each living interior particle takes the smallest colour that none of
// its spring neighbours or contacts has. Boundary (wire) and dead particles are not moved by the solver and
// get no colour. Fills topo.colourOffset and topo.colourOrder (particles of a colour in increasing index).
void colourParticles(const std::vector<uint32_t>& alive, Topology& topo);

// True when no spring or contact joins two particles of the same colour and every living interior
// particle has exactly one colour (tests, and a guard before a solve).
bool isValidColouring(const std::vector<uint32_t>& alive, const Topology& topo);

}  // namespace gb
