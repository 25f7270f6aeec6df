#pragma once
// Self-collision of the film (Section 8). Between frames, a uniform hash grid finds the pairs of particles
// that may touch during the next frame; the forces stage of both backends then repels the pairs closer
// than Params::collisionDistance (a gather over each particle's contact list, pair forces equal and
// opposite, tangential motion free so that the sheets slip). Bursting on a hard impact (lambda_col) is not
// done yet: see docs/model.md.

#include "film.h"

namespace gb {

// Fills film.topology.contacts: for every living particle, the living particles within
// collisionDistance + margin that are not its one-ring neighbours and that lie across the film from it
// (their separation makes an angle under 45 degrees with one of the two normals, so neighbours along the
// same sheet are left out). The list is symmetric and sorted. Returns the number of pairs.
size_t findContacts(const Params& params, float margin, Film& film);

}  // namespace gb
