#pragma once
// The stages of one simulation step (docs/architecture.md "The step's stages"), each a function of one element that
// reads explicit inputs and writes only that element's outputs. This file is the definition both backends
// follow: each stage's GLSL kernel(s) in kernels/ (kernel_list.h) run the function of the same name per element.
//
// Gather, never scatter: every per-particle result is summed by the particle itself over its CSR one-ring,
// in CSR order. Propagation (air transfer) is a Jacobi pass from a front buffer into a back buffer.

#include <span>

#include "kernels/shared/shared_step.h"
#include "model/params.h"
#include "model/state.h"
#include "model/wire_frame.h"

namespace gb {

// What a step needs besides the state, computed once per step on the host: one definition for both backends,
// kernels/shared/shared_step.h, which the GPU receives as it is (one per step of a batch, in a storage buffer). Its
// vectors are vec4; these read and write them as the CPU's types.
using StepUniforms = gpu::StepUniformsBlock;
inline Vec3 toVec3(const gpu::vec4& v) { return {v.x, v.y, v.z}; }
inline gpu::vec4 toVec4(const Vec3& v) { return {v.x(), v.y(), v.z(), 0.0f}; }
// The wand tips at the start of the step, the air sources of Eq. (5).
WandState wandsOf(const StepUniforms& u);
void setWands(StepUniforms& u, const WandState& wands);
// The wire frame at the end of the step, for the boundary particles.
WireFrame wireNextOf(const StepUniforms& u);
void setWireNext(StepUniforms& u, const WireFrame& frame);

// ---- Stage 1-2: geometry -------------------------------------------------------------------------------
// Pass 1, per triangle t: its area-weighted normal and the mixed Voronoi area (Meyer et al. 2003) of each of
// its corners. Each triangle is computed once instead of once per corner.
void triangleGeometry(const Topology& topo, State& s, size_t t);
// triangleGeometry of the triangles [first, last), four at a time in the lanes of float_lanes.h: the same floats.
void triangleGeometries(const Topology& topo, State& s, size_t first, size_t last);
// Pass 2, per particle i: unit vertex normal (sum of its triangles' area-weighted normals) and mixed Voronoi
// area (sum of its corners' areas), gathered in CSR order.
void vertexGeometry(const Topology& topo, State& s, size_t i);
// Both passes over the whole film, serially: for code outside the step (film creation, pinch-off, tests).
void computeGeometry(const Topology& topo, State& s);
// Both passes for the triangles around `particles` and for the particles themselves, after the mesh grew there (a
// strip at the wire): the rest of the film keeps the geometry it had, and the per-triangle arrays grow to fit.
void computeGeometryAround(const Topology& topo, State& s, std::span<const uint32_t> particles);
// Sizes the per-triangle arrays for the topology.
void fitTriangleArrays(const Topology& topo, State& s);
// A 64-bit hash of everything the geometry depends on (the positions, the triangles, the counts): equal keys mean
// the geometry computed for one holds for the other. The CPU stepper's geometry stage skips its work when the film
// still has the key of the geometry last computed: `giantbubble run` computes it for each frame's figures
// (Simulation::stats) and the next step would compute it again from the same positions (0.6 ms of a 10 ms frame of
// the default film).
uint64_t geometryKey(const Topology& topo, const State& s);

// Signed volume of the tetrahedron (origin, triangle t); their sum is the enclosed volume of a closed
// film and the volume swept between an open film and the apex.
float triangleVolume(const Topology& topo, const State& s, size_t t, const Vec3& origin);
// The signed volume of the cone from `origin` to the triangle (a, b, c), the one formula of triangleVolume and
// of the energy budget's triangleVolumeAtStart.
float coneVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& origin);
// triangleVolume of the triangles [first, last) into volumes[first, last), or with atStepStart the energy budget's
// triangleVolumeAtStart: four triangles at a time in the lanes of float_lanes.h, the same floats as one at a time.
// A closed film's volume is summed on every sweep of a step, and the triangles' corners are most of the work.
void triangleVolumes(const Topology& topo, const State& s, const Vec3& origin, bool atStepStart, size_t first,
                     size_t last, float* volumes);

// Pairwise sum with a fixed tree shape (level by level, a[k] = a[2k] + a[2k+1]): the reduction both
// backends use for the volume, so that they add in the same order.
float treeSum(std::vector<float> values);
// treeSum adding within `values`, which it leaves changed: for scratch arrays, which it then need not copy.
float treeSumInPlace(std::span<float> values);

// ---- Stage 3: film state (Section 5.1) ---------------------------------------------------------------
// Eq. (4): elasticity from thickness e (m) and lifetime (s). Marangoni while young, Gibbs after, the Gibbs
// branch held at its value at Params::gibbsFloorThickness for thinner film. The paper's formulas are divided by k so
// that w_E carries the unit N/m (docs/model.md).
float elasticityOf(const Params& p, float thickness, float lifetime);

// Physical model: the film's tension 2 gamma (N/m), gamma following the surfactant per area through Gibbs-Marangoni
// elasticity, gamma = gamma_0 + (E_G / 2) ln(e_0 / e) (a stretched film has less surfactant per area), kept within
// [gamma_0 / 2, 2 gamma_0]. e is the thickness the particle's surfactant gives, surfactantLiquid / area: the film's
// thickness had none of its liquid drained.
float filmTension(const Params& p, float thickness);

// Physical model: the tension's potential energy (J) on a particle's area `area` made with `liquid`
// (surfactantLiquid, m^3), the W whose derivative dW/da is filmTension at the thickness liquid / a: 2 gamma a less
// E_G (clamp(a, a_lo, a_hi) - a_lo).
// Where gamma follows the area (between the clamp's areas a_lo and a_hi), 2 gamma a also counts the rise of gamma
// as if it had held over the whole area, which the tension never did work against. The step freezes gamma, so a
// film it stretched by da gains E_G da of "2 gamma a" when gamma is refreshed, but none of W: counted as 2 gamma a,
// a film at rest would seem to gain energy from nothing.
double filmTensionEnergy(const Params& p, double liquid, double area);

// Physical model, per particle i: -sum over its triangles t of T_t grad_i A_t, T_t the mean tension 2 gamma of
// t's corners: the discrete mean-curvature force 2 gamma (2 H) A_i n on a smooth film, and an in-plane pull
// where the tension varies (Marangoni). Needs the geometry stage's triangle normals.
Vec3 areaTensionForce(const Topology& topo, const State& s, size_t i);

// Thickness e_i = liquid / A_Vor, elasticity E_i (the paper) or the film tension 2 gamma_i (physical
// model: the same N/m slot), and the particle's age.
void filmState(const Params& p, float dt, State& s, size_t i);

// ---- Stage 4: air inflow (Section 5.2.1) ---------------------------------------------------------------
// Eq. (5): air flow (m^3/s) at a point, created by the moving wands.
Vec3 airInflowAt(const Params& p, const StepUniforms& u, const Vec3& position);
void airInflow(const Params& p, const StepUniforms& u, State& s, size_t i);

// ---- Stage 5: air flow transfer (Section 5.2.2, Algorithm 2) --------------------------------------------
// Eqs. (7)-(8) as a Jacobi gather: particle i receives the air of each neighbour j whose air points towards
// it (a_dir > lambda_air), weighted by a_dir; its own old air is dropped ("delete air_i"). End (boundary)
// particles are assigned the fresh inflow instead. Reads airFlow, writes airFlowNext[i].
void airTransfer(const Params& p, const Topology& topo, State& s, size_t i);

// ---- Stage 6: forces, Eq. (2) --------------------------------------------------------------------------
// Internal forces on particle i, the ones the implicit step takes into its energy: surface tension Eq. (3)
// with the spring's stiffness the mean of its two particles' E (so the pair forces cancel exactly) or the
// physical area tension, spring-projected damping (Algorithm 1), and the self-collision contacts.
Vec3 internalForce(const Params& p, const Topology& topo, const State& s, size_t i);
// External forces on particle i, the ones both integrators keep explicit: gravity, and the air force, Eq. (9)
// on an open film or the transferred air of Eq. (10) on a closed bubble at pressure P_cur.
Vec3 externalForce(const Params& p, const StepUniforms& u, float pressure, const State& s, size_t i);
// Open film: the air force of Eq. (9) acts on the film relative to the air: kappa ((air . n) - Area_wm (v . n))
// A_Vor n, the air's speed being its flow over the frame's area. externalForce holds the first part; this is
// the coefficient kappa Area_wm A_Vor (N s/m) of the second, a damping of the film's normal speed towards the
// air's, faded out below 5 cm/s of air speed (still air holds nothing: only airDrag acts). Without it Eq. (9) pushes
// with the same force however fast the film already moves, and a film drawn at real arm speeds runs away (docs/model.md
// "Air coupling"). The implicit step takes it as a dissipation.
float airCoupling(const Params& p, const StepUniforms& u, const State& s, size_t i);
// The air coupling at full strength (air at or above 5 cm/s) for a frame of area Area_wm (m^2): kappa Area_wm
// A_Vor (N s/m). airCoupling fades it out in still air; stableTimeStep bounds the explicit step with it.
float fullAirCoupling(const Params& p, float wireArea, float voronoiArea);

// dV/dx_i of a closed film's enclosed volume V = sum_t x_a . (x_b x x_c) / 6: a sixth of the twice-area normals of
// particle i's triangles (the geometry stage's). Over a closed film these sum to zero exactly.
Vec3 volumeGradient(const Topology& topo, const State& s, size_t i);

// Closed bubble, Eqs. (10)-(11): the excess of Boyle's pressure P_cur = P_0 V_0 / V over P_0 times the volume's
// gradient (volumeGradient): on a smooth film the particle's area along its normal. It pushes a compressed bubble out
// and pulls an expanded one in. Taken as the gradient, it is the force of the gas's energy exactly: its sum over the
// film is zero, and it does the work the gas's energy change says. The Voronoi area along the vertex normal, its
// smooth-film approximation, sums to up to 0.17 N on a crumpled bubble and does up to 0.04 W of work the gas never
// pays for. The implicit step evaluates it at the volume of its current iterate
// (implicit_euler.h): at the step's start it is unstable at h = 0.02 s for a bubble of tens of centimetres.
Vec3 boyleForce(const Params& p, float pressure, const Topology& topo, const State& s, size_t i);
// Its scalar factor, the excess of Boyle's pressure over P_0 (Pa), for a gradient laid out elsewhere.
float boyleExcess(const Params& p, float pressure);
// Explicit integrator: the whole of Eq. (2), internal + external + linear air drag + air coupling (open) or
// Boyle (closed).
void forces(const Params& p, const StepUniforms& u, float pressure, const Topology& topo, State& s, size_t i);
// Implicit integrator: the external forces only (drag and the internal forces are in the solver).
void externalForces(const Params& p, const StepUniforms& u, float pressure, State& s, size_t i);

// Eq. (11), Boyle's law: P_cur = P_0 V_0 / V_cur.
float boylePressure(const Params& p, float referenceVolume, float currentVolume);
// The energy the bubble's air stores at volume V against the outside air, the work Boyle's excess pressure does
// when the bubble returns to V_0: -integral from V_0 to V of (P_cur - P_0) dV' = P_0 V_0 ln(V_0 / V) + P_0 (V - V_0),
// zero at V_0 and positive either side (J). The implicit step's objective holds it (implicit_euler.h): a
// compressed bubble's air pushes the film out, its energy going into the film's motion and tension. CPU
// diagnostics only (FrameStats), in double: the two terms cancel to a small difference.
double boyleGasEnergy(const Params& p, double referenceVolume, double currentVolume);

// ---- Stage 7: semi-implicit Euler, Eqs. (12)-(13) --------------------------------------------------------
// Interior particles integrate their force and stop at the floor (y = 0), keeping their sliding velocity;
// boundary particles are carried to the wire frame at the end of the step, with the velocity that motion
// implies.
void integrate(const StepUniforms& u, const Topology& topo, State& s, size_t i);

// ---- Stage 8 (filmFlow 0): position-dependent drainage (Section 6.2, Eqs. 14-15) --------------------------
// Eq. (14): how closely the direction from sender x_i to receiver x_j follows gravity g, MAX(cos, 0).
float drainageDirection(const Vec3& xi, const Vec3& xj, const Vec3& g);

// Pass 1: particle i sends out_i = w_i min(1, dt rate D_i / Sticky) of its liquid (dt: StepUniforms::drainageDt), D_i =
// sum of d_dir(i->k) over its neighbours; stores out_i and D_i.
void drainageOutflow(const Params& p, float dt, const Topology& topo, State& s, size_t i);

// Pass 2, Eq. (15) as a gather: particle j keeps what it did not send and receives out_i d_dir(i->j) / D_i
// from each neighbour i. What leaves a particle is exactly what its downhill neighbours receive, so the
// total liquid is conserved to float rounding.
void drainageGather(const Params& p, const Topology& topo, State& s, size_t j);

// ---- Stage 8 (default): film flow (docs/model.md "Film flow") -------------------------------------------
// The depth-averaged thin-film flow of Huang et al. 2020 on the particles: the liquid moves over the film's surface
// with velocity u (relative to the surface, tangent to it), carrying thickness e and surfactant Gamma:
//   de/dt = -div(e u),  d(Gamma)/dt = -div(Gamma u)  (plug flow: the surfaces move with the liquid),
//   du/dt = g_t - (E_M / (rho e)) grad ln Gamma + (2 k_air / (rho e)) (w_t - u) - (12 mu phi / (rho e^2)) u
//           + nu_f lap u,
// g_t gravity along the surface, E_M the Marangoni elasticity, w_t the air's velocity past the film along it (the
// wands' air flow less the film's own velocity), phi the surfaces' rigidity, nu_f the in-plane viscosity. The
// velocity is Jacobi-implicit in its rates (any dt is stable); each particle sends liquid across its one-ring's edges
// with its own velocity (flowSweptArea), the net flux of each edge exactly antisymmetric (filmFlowEdgeFlux), so liquid
// is conserved to float rounding.

// The terms of particle i's velocity equation, from the state at the flow's start.
struct FilmFlowTerms {
  Vec3 gravity = Vec3::Zero();        // g_t (m/s^2)
  Vec3 marangoni = Vec3::Zero();      // -(E_M / (rho e)) grad ln Gamma, tangential (m/s^2)
  Vec3 air = Vec3::Zero();            // w_t, the air's velocity past the film along its surface (m/s)
  float airRate = 0.0f;               // 2 k_air / (rho e) (1/s): the air's shear pulls u towards w_t at this rate
  float wallRate = 0.0f;              // 12 mu phi / (rho e^2) (1/s): the surfaces' friction
  float viscosityRate = 0.0f;         // nu_f (4 / k) sum_j 1 / |d_ij|^2 (1/s), the diagonal of -nu_f lap
  Vec3 viscosityPull = Vec3::Zero();  // nu_f (4 / k) sum_j u_j / |d_ij|^2 (m/s^2), the off-diagonal part
  float spacingSquared = 0.0f;        // k / sum_j 1 / |d_ij|^2 (m^2): the ring's squared spacing (harmonic mean)
};
// grad f at particle i from its one-ring: (2 / k) sum_j (f_j - f_i) d_ij / |d_ij|^2 (exact for a linear f on a
// regular ring); lap f: (4 / k) sum_j (f_j - f_i) / |d_ij|^2. Over the living neighbours (k of them). f = ln Gamma
// is read from logSurfactant, each particle's as pass 0 keeps it (filmFlowLogSurfactant).
FilmFlowTerms filmFlowTerms(const Params& p, const StepUniforms& u, const Topology& topo, const State& s, size_t i,
                            std::span<const float> logSurfactant);
// ln(Gamma / Gamma_0) = ln(s e / e_0), s the surfactant per liquid (at least kLeastSurfactant), e the thickness (at
// least kThinnestFlowingFilm), e_0 a new film's: of order one, so that the gradient's differences f_j - f_i keep a
// float's precision near one (ln Gamma itself, about ln 1e-6, would cancel to ulps of 14 on a nearly even film).
float logSurfactant(const Params& p, float surfactant, float thickness);
// A_i / k_i: particle i's area per spring, its share of the dual edges (flowSweptArea); 0 without springs.
float flowAreaShare(const Topology& topo, const State& s, size_t i);
// flowSweptArea of particle i towards neighbour j, with i's new velocity (flowVelocityNext) and the two particles'
// flowAreaShare as pass 1 stored them.
float filmFlowSweptArea(float dt, const State& s, uint32_t i, uint32_t j);
// The liquid particle i sends to neighbour j in dt (m^3): what i's velocity sweeps times e_i and i's limit.
float filmFlowSent(float dt, const State& s, uint32_t i, uint32_t j);
// The liquid the edge from i to j carries from i to j in dt (m^3, negative: from j to i): what i sends less what j
// sends. Exactly the negative of filmFlowEdgeFlux(j, i).
float filmFlowEdgeFlux(float dt, const State& s, uint32_t i, uint32_t j);

// Pass 0: particle i's logSurfactant into logSurfactant[i], for pass 1's gradients: one logarithm a particle, not one
// an edge end (the shader computes each where it reads it).
void filmFlowLogSurfactant(const Params& p, const State& s, size_t i, std::span<float> logSurfactant);
// Pass 1: u_i's new value, (u + dt (g_t + c marangoni + airRate w_t + viscosityPull)) / (1 + dt (airRate + wallRate +
// viscosityRate)), projected on the tangent plane; 0 on the wire (the liquid sticks to it) and for a dead particle.
// c <= 1 caps the Marangoni diffusivity D = E_M / (rho e) dt / (1 + dt rates) at D dt = kMarangoniCourant spacing^2.
// Writes flowVelocityNext[i], and flowAreaShare[i] for the passes after it.
void filmFlowVelocity(const Params& p, const StepUniforms& u, const Topology& topo, State& s, size_t i,
                      std::span<const float> logSurfactant);
// Pass 2: the share of its outflow particle i can give, min(1, kLargestOutflowShare (w_i - e_b A_i) / outflow_i), e_b
// the black film's thickness (the disjoining pressure stops drainage there); keeps its surfactant as
// surfactantBefore for pass 3.
// swept keeps the swept area (filmFlowSweptArea) of each spring from each of its ends for pass 3 (flowSweptSlot): on
// the CPU a value per edge and direction spares the gathers computing every edge's two areas again (the shader, whose
// device has no binding to spare for it, computes them again, to the same floats).
void filmFlowLimit(const Params& p, float dt, const Topology& topo, State& s, size_t i, std::span<float> swept);
// Where filmFlowLimit keeps the swept area of `spring` from its end `from`: 2 spring, or 2 spring + 1 from its second
// end (Topology::springEnds). The two of a spring are neighbours: slot ^ 1 is the other end's.
inline size_t flowSweptSlot(const Topology& topo, uint32_t spring, uint32_t from) {
  return 2 * size_t{spring} + (topo.springEnds[2 * size_t{spring}] == from ? 0 : 1);
}
// Pass 3, a gather: particle j's liquid and surfactant after its edges' fluxes (what each end sends, filmFlowSent,
// its surfactant with it), less what evaporates (evaporatedLiquid; its surfactant stays); u becomes the new
// velocity.
// Reads the swept areas pass 2 kept, j's own to i and i's to j, from their spring's two slots.
void filmFlowGather(const Params& p, float dt, const Topology& topo, State& s, size_t j, std::span<const float> swept);

// ---- Stability -----------------------------------------------------------------------------------------
// Largest elasticity Eq. (4) can give the film: the Gibbs peak 0.5 w_E, or the Marangoni value of a young
// film twice the initial thickness, whichever is larger.
float elasticityBound(const Params& p);

// Largest explicit substep that keeps semi-implicit Euler stable for every particle (Gershgorin bound on
// the stiffness of its springs, damping, drag and, on an open film, the air coupling at full strength with
// the film's area as a bound on the frame's; and the pressure of a closed film), times Params::stabilitySafety.
float stableTimeStep(const Params& p, const Topology& topo, const State& s, float pressure, float volume);

}  // namespace gb
