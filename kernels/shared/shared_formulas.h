// The formulas and constants that the CPU stages (cpu-reference/) and their GLSL twins share, defined once and
// compiled as C++ (namespace gb) and as GLSL (common.glsl includes it). Each says where it is used.
#ifdef __cplusplus
#pragma once
#include <cmath>
namespace gb {
using std::sqrt;
#define GB_CONST inline constexpr
#define GB_FORMULA inline constexpr
#define GB_REAL_FORMULA \
  template <class Real> \
  inline constexpr Real
#define GB_REAL Real
#define GB_PRECISE
#else
#define GB_CONST const
#define GB_FORMULA
#define GB_REAL_FORMULA float
#define GB_REAL float
// Where the C++ twin's rounding is the rule (a threshold both backends must draw alike), no fused multiply-add.
#define GB_PRECISE precise
#endif

// The film's thickness at the dip, e0 = w_e x 100 um (Section 5.1, areaWeight; initialThickness).
GB_FORMULA float initialThicknessOf(float areaWeight) { return areaWeight * 100e-6f; }

// The energy k/2 stretch^2 of a spring of stiffness k (Eq. 3 with k = (E_i + E_j)/2), or of a contact's penalty
// (k_c, stretch d_c - |x_i - x_j|). Each particle's share of it is half (the energy budget's terms).
GB_REAL_FORMULA springEnergyOf(GB_REAL stiffness, GB_REAL stretch) {
  return GB_REAL(0.5) * stiffness * stretch * stretch;
}

// The physical model's surface tension gamma stays within these multiples of gamma_0 (filmTension), so a film's
// tension 2 gamma, and a triangle's within the step (triangleTensionOf), within [gamma_0, 4 gamma_0].
GB_CONST float kLowestGammaFactor = 0.5f;
GB_CONST float kHighestGammaFactor = 2.0f;
GB_FORMULA float lowestTension(float surfaceTension) { return 2.0f * (kLowestGammaFactor * surfaceTension); }
GB_FORMULA float highestTension(float surfaceTension) { return 2.0f * (kHighestGammaFactor * surfaceTension); }

// The largest move of a particle in one sweep of vertex block descent, in its shortest one-ring springs
// (withinTrustRegion; cpu-reference/solver/implicit_euler.cpp says why).
GB_CONST float kTrustRegion = 0.25f;
// A coarse-correction patch moves at most this many trust regions of its shortest spring: half a spring
// (cpu-reference/solver/coarse_correction.cpp says why).
GB_CONST float kPatchTrustScale = 2.0f;

// Below this normal air speed (m/s) the air coupling fades out: still air only drags (airCoupling).
GB_CONST float kStillAirSpeed = 0.05f;

// Film flow (filmFlowVelocity, filmFlowLimit, filmFlowGather). Film thinner than this counts as this thick in the
// flow's rates, which divide by the thickness (m): a particle whose liquid all ran off still has a finite rate.
GB_CONST float kThinnestFlowingFilm = 1e-9f;
// A particle sends at most this share of its liquid above the black film's in one flow step (the flow's limiter):
// with the outflow capped every particle keeps its black film whatever the speed.
GB_CONST float kLargestOutflowShare = 0.5f;
// The Marangoni stress diffuses the surfactant (and the liquid it carries) with the diffusivity
// D = E_M / (rho e) dt / (1 + dt rates) of the velocity update: filmFlowVelocity scales it down where D dt exceeds
// this share of the particle's squared spacing, the largest an explicit transport step carries without overshooting.
GB_CONST float kMarangoniCourant = 2.0f;
// The surfactant per liquid that counts in ln(Gamma) is at least this (relative to a new film's): ln of 0 is not a
// tension.
GB_CONST float kLeastSurfactant = 1e-6f;

// The film area that particle i's liquid velocity u_i sweeps across the one-ring edge to neighbour j in dt (m^2):
// dt max(u_i . d, 0) / |d| times the edge's dual length 2 (A_i / k_i + A_j / k_j) / |d|, A the Voronoi areas, k the
// particles' spring counts (on a regular mesh the dual edge |d| / sqrt(3)); `along` is u_i . d, d = x_j - x_i. Each
// particle sends with its own velocity (flux splitting): a thin particle, slowed by its friction, is not emptied at a
// thick neighbour's speed. The edge's net flux, i's sending less j's, is computed alike from both ends and so is
// exactly antisymmetric: what leaves one particle enters the other to the last bit.
GB_FORMULA float flowSweptArea(float dt, float shareI, float shareJ, float along, float lengthSquared) {
  return along > 0.0f ? dt * (2.0f * (shareI + shareJ)) * along / lengthSquared : 0.0f;
}

// The liquid a particle of area `area` loses by evaporation in dt (m^3; filmFlowGather): the film thins at `rate`
// (evaporationRate) until it is black film, which holds too little water to lose more (docs/model.md "Evaporation").
GB_FORMULA float evaporatedLiquid(float rate, float dt, float liquid, float area, float blackFilmThickness) {
  const float aboveBlackFilm = liquid - blackFilmThickness * area;
  const float most = rate * dt * area;
  return aboveBlackFilm <= 0.0f ? 0.0f : (aboveBlackFilm < most ? aboveBlackFilm : most);
}

// Self-collision (cpu-reference/topology/collision.h, findContacts; kernels/contacts/contact_pairs.comp). A pair's
// margin: how much closer than the collision distance it is searched for, at `closing` a bound on the speed at which it
// closes, capped at kMaxContactMargin (m: a film faster than 2.5 m/s relative to itself bursts anyway).
GB_CONST float kMaxContactMargin = 0.05f;
GB_FORMULA float contactMargin(float frameTime, float slack, float closing) {
  GB_PRECISE const float margin = frameTime * closing + slack;
  return margin < kMaxContactMargin ? margin : kMaxContactMargin;  // std::min(kMaxContactMargin, margin)
}
// A pair lies across the film when its separation d makes less than 45 degrees with either normal: (n . d)^2 over
// 1/2 |d|^2 for one of them.
GB_CONST float kAcrossCosineSquared = 0.5f;
GB_CONST float kAcrossCosine = 0.70710678f;  // its root, for the search's bounds (partnerRadius)
GB_FORMULA bool liesAcross(float alongI, float alongJ, float lengthSquared) {
  return alongI * alongI > kAcrossCosineSquared * lengthSquared ||
         alongJ * alongJ > kAcrossCosineSquared * lengthSquared;
}
// A listed pair's rest distance (collision.h says why): the collision distance, or the largest of its separation and
// the rest distance it had in the last list, whichever is less.
GB_FORMULA float contactRestDistanceAfter(float collisionDistance, float previousRest, float separation) {
  const float kept = previousRest < separation ? separation : previousRest;  // std::max(previousRest, separation)
  return kept < collisionDistance ? kept : collisionDistance;                // std::min(collisionDistance, kept)
}

// The per-frame film rules between steps (cpu-reference/topology/film_checks.h lists them; the device's
// film_statistics_terms.comp counts where they would act). The device's checks fire this much (relative) before the
// rules' thresholds: float sums and lengths on the device round differently from the CPU's by a few units in the last
// place (1e-7 relative); a thousand times that is never missed. A frame near a threshold brings the state back and
// lets the CPU rules decide exactly.
GB_CONST float kFilmCheckMargin = 1e-4f;
// A film moving faster than this (m/s) has blown up: real giant bubbles never approach it (Simulation's stability
// check).
GB_CONST float kUnstableSpeed = 100.0f;
// A particle this close above the floor (m) touches it: a soap film bursts on a dry floor.
GB_CONST float kFloorTouching = 1e-3f;
// Plastic yield (yieldStretchedSprings): a spring stretched past yieldStretch times its rest, both ends at least
// yieldThickness thick, yields.
GB_FORMULA bool springYields(float length, float rest, float thinnerEnd, float yieldStretch, float yieldThickness) {
  return !(thinnerEnd < yieldThickness) && length > yieldStretch * rest;
}
// Contraction (contractSlackSprings): a slack spring whose ends are both thinner than the dip contracts.
GB_FORMULA bool springContracts(float length, float rest, float thickerEnd, float dipThickness) {
  return length < rest && thickerEnd < dipThickness;
}
// The rest length a contracting spring of `length` goes to (contractSlackSprings): as taut as new film
// (springPrestrain), or with energyNeutralContraction stretched only as far as it was compressed.
GB_FORMULA float tautRestLengthOf(float length, float rest, float springPrestrain, int energyNeutralContraction) {
  if (energyNeutralContraction == 0) return length * (1.0f - springPrestrain);
  const float slack = rest - length, most = springPrestrain * length;
  return length - (slack < most ? slack : most);  // length - std::min(slack, most)
}
// The contraction (contractSlackSprings) takes every slack spring the same share s of the way from its rest length
// to its taut one. A spring of stiffness k compressed by a = rest - length, going c = rest - taut, then holds
// k/2 (s c - a)^2 instead of k/2 a^2: its energy grows by s^2 k/2 c^2 - s k a c. Summed over the springs, s^2 Q - s L
// with Q the sum of these quadratic terms and L of the linear ones.
GB_FORMULA float contractionQuadraticOf(float stiffness, float rest, float taut) {
  return 0.5f * stiffness * (rest - taut) * (rest - taut);
}
GB_FORMULA float contractionLinearOf(float stiffness, float length, float rest, float taut) {
  return stiffness * (rest - length) * (rest - taut);
}
// The spring energy the contraction adds taking its springs `share` of the way: s^2 Q - s L.
GB_FORMULA float contractionEnergyOf(float share, float quadratic, float linear) {
  return share * share * quadratic - share * linear;
}
// The share of the way the contraction takes every slack spring: all of it where the energy that adds, Q - L, is
// within the allowance, else the root of s^2 Q - s L = allowance (at least L / Q, where the springs' energy is what
// it was: the first part of the way relieves their compression).
GB_FORMULA float contractionShareOf(float quadratic, float linear, float allowance) {
  if (!(quadratic > 0.0f) || !(quadratic - linear > allowance)) return 1.0f;  // Q = 0: no spring has a way to go
  const float paid = allowance > 0.0f ? allowance : 0.0f;
  return (linear + sqrt(linear * linear + 4.0f * quadratic * paid)) / (2.0f * quadratic);
}
// A contracting spring's new rest length, `share` of the way from `rest` to `taut` (exactly `taut` all the way).
GB_FORMULA float contractedRestLengthOf(float rest, float taut, float share) {
  return share == 1.0f ? taut : rest + share * (taut - rest);
}
// The squared length of a spring (x, y, z its ends' difference), summed as Eigen's norm() sums a Vec3, x^2 + (y^2 +
// z^2): the merges' median spring is chosen among these on the device (kernels/statistics/crowded_springs.comp) and its
// square root taken on the CPU, which must give the median of the CPU's lengths to the last bit.
GB_FORMULA float squaredLengthOf(float x, float y, float z) {
  GB_PRECISE const float squared = x * x + (y * y + z * z);
  return squared;
}
// A crowded spring merges its ends only if shorter than this fraction of the film's median spring.
GB_CONST float kCrowdedEdge = 0.5f;
// Crowding (mergeCrowdedParticles): a slack spring with an end at least as thick as the dip may merge its ends (if
// it is also short against the film's median spring).
GB_FORMULA bool springCrowded(float length, float rest, float thickerEnd, float dipThickness) {
  return length < rest && !(thickerEnd < dipThickness);
}
// Payout at the wire (payOutFilmAtWire): a rung stretched past growthStretch times its rest draws new film.
GB_FORMULA bool rungPaysOut(float length, float rest, float growthStretch) { return length > growthStretch * rest; }
// The impact of two film particles meeting at approach speed v (impactNumber, collision.h): m_A v^2 / E.
GB_FORMULA float impactNumberOf(float filmInertia, float approachSpeed, float elasticity) {
  return approachSpeed <= 0.0f || elasticity <= 0.0f ? 0.0f : filmInertia * approachSpeed * approachSpeed / elasticity;
}

#undef GB_CONST
#undef GB_FORMULA
#undef GB_REAL_FORMULA
#undef GB_REAL
#undef GB_PRECISE
#ifdef __cplusplus
}  // namespace gb
#endif
