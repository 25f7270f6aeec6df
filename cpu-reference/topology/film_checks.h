#pragma once
// What the per-frame film rules between steps (Simulation::advanceFrame) need to know of the film before they act,
// reduced to a few figures: whether the film blew up, how near it is to the floor and to the wand tips, whether a
// tip is inside a bubble, its thinnest particle (burst by thinning), the hardest impact of its contact pairs, and
// how many springs each rest-length rule would change. A stepper that holds the state on its device reduces them
// there (DeviceResidency::probeFilm, kernels/statistics/film_statistics_terms.comp) with every threshold loosened by
// kFilmCheckMargin (shared_formulas.h): a frame whose figures say that no rule acts needs no state in host memory, and
// a frame whose figures come near a threshold brings the state back and lets the CPU rules decide exactly
// (docs/backends.md).

#include <array>
#include <limits>

#include "kernels/shared/shared_formulas.h"
#include "model/film.h"

namespace gb {

// Where the checks look: the two wand tips and the frame's length (the impact test's time to close).
struct FilmProbe {
  Vec3 origin = Vec3::Zero();  // apex of the cone volumes of the statistics (FilmSums)
  std::array<Vec3, 2> tips{Vec3::Zero(), Vec3::Zero()};
  float frameTime = 0.0f;
  bool atPresentPositions =
      true;  // the geometry and film state brought up to the positions first (DeviceResidency::probeFilm)
};

struct FilmChecks {
  static constexpr float kInfinity = std::numeric_limits<float>::infinity();
  size_t particles = 0;      // living particles: with none no rule acts
  bool unstable = false;     // a living particle with a non-finite position or velocity, or faster than kUnstableSpeed
  float lowest = kInfinity;  // height of the lowest living particle (m)
  std::array<float, 2> nearestTip{kInfinity, kInfinity};  // distance from each tip to the nearest living particle (m)
  std::array<float, 2> winding{0.0f, 0.0f};               // the film's winding number about each tip (windingNumber)
  float thinnest = kInfinity;                             // thickness of the thinnest living particle with area (m)
  float hardestImpact = 0.0f;  // impact number of the hardest contact pair closing within the frame (hardestImpact)
  float yielding = 0.0f;       // springs the yield rule would lengthen (yieldStretchedSprings, on an open film)
  float slack = 0.0f;          // springs the contraction would take (contractSlackSprings, on a closed film)
  float crowded = 0.0f;        // slack springs with a thick end (mergeCrowdedParticles' candidates)
  // The spring energy the contraction adds taking its springs the share s of the way, s^2 contractionQuadratic -
  // s contractionLinear (contractionEnergy, J): exact, not loosened.
  float contractionQuadratic = 0.0f, contractionLinear = 0.0f;
  float rungsPastGrowth = 0.0f;  // rungs past growthStretch (payOutFilmAtWire)
  // The wire's band (wireBandWidth): the rungs, their summed rest length (m), the springs along the wire and their
  // summed length (m).
  float rungs = 0.0f, rungRest = 0.0f, wireEdges = 0.0f, wireEdgeLength = 0.0f;
};

// Whether a particle at x moving at v is stable (Simulation's stability check): finite, and no faster than
// kUnstableSpeed over `margin` more.
inline bool particleStable(const Vec3& x, const Vec3& v, float margin = 0.0f) {
  return x.allFinite() && v.allFinite() && v.norm() * (1.0f + margin) <= kUnstableSpeed;
}

// The checks of `film` in host memory, each threshold loosened by `margin` (0: the rules' own thresholds): the
// reference of the device's (film_statistics_terms.comp computes the same terms per particle).
FilmChecks checkFilm(const Params& params, const Film& film, const FilmProbe& probe, float margin);

}  // namespace gb
