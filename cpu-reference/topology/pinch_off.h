#pragma once
// Pinch-off: the film leaves the wands as a free bubble. When the performer closes the wands, the film's
// open boundary (the wire loop) is sewn shut with a cap, so the film becomes a closed, consistently
// oriented manifold with outward normals; the wire lets go, and from then on Boyle's pressure,
// Eqs. (10)-(11), acts with V_0 taken at closure.

#include "model/film.h"

namespace gb {

// The boundary loop of an open film, in the direction its triangles traverse their boundary edges; empty
// for a closed film. Throws std::runtime_error if the boundary is not a single loop (a torn film).
std::vector<uint32_t> boundaryLoop(const Topology& topology);

// Turns the triangles sewn onto a film's boundary loop (a pinch-off seam, a strip of new film at the wire) so
// that they cross each loop edge the other way round from the film: flips them all if they run
// loop[0] -> loop[1] as the film does.
void orientAgainstLoop(const std::vector<uint32_t>& loop, std::vector<uint32_t>& seam);

// Zips a collapsed loop shut, or caps it with rings shrunk towards its centroid (about one ring per loop spacing,
// each with fewer particles) and a particle at the centroid; new springs rest prestrained at their length, new
// particles get the film's material. The seam's particles are wetted to the film's mean thickness with liquid from
// the wire and, where it runs short, from the rest of the film: film + wire liquid is conserved. Sets the reference
// volume and origin of Eq. (11) and clears the wire flags. Returns false (film unchanged) when the film is already
// closed.
bool pinchOff(const Params& params, Film& film);

}  // namespace gb
