// One definition of the model's parameter block, compiled as C++ (cpu-reference/model/params.h includes it)
// and as GLSL (every compute shader includes it). Every parameter of the paper (Table 2 and Sections 5-7)
// in SI units, the paper's symbol in the comment; docs/model.md maps the paper's scale to SI.
// Only 4-byte scalars, so the std430 layout is the C layout with no padding (checked by a test).
#ifdef __cplusplus
#pragma once
#define GB_DEFAULT(value) = value
namespace gb {
#else
#define GB_DEFAULT(value)
#endif

struct Params {
  // --- Time integration (Section 5.3; docs/model.md "Integrators") ---
  float frameTime GB_DEFAULT(0.02f);       // h, Table 2: 0.02 s. One frame of wand input
  int integrator GB_DEFAULT(1);            // 1: implicit Euler solved by vertex block descent (one step per frame);
                                           // 0: the paper's semi-implicit Euler, Eqs. (12)-(13), in stable substeps
  int solverSweeps GB_DEFAULT(6);          // vertex block descent sweeps per implicit step
  int coarseIterations GB_DEFAULT(0);      // conjugate-gradient iterations of the step's coarse correction (patch
                                           // system, coarse_correction.h) halfway through the sweeps; 0: none. Off by
                                           // default: the default performance is tuned to the sweeps alone
                                           // (docs/model.md "Coarse correction")
  int coarsePatchRings GB_DEFAULT(4);      // a coarse-correction patch: the particles within this many springs
  int energyBudget GB_DEFAULT(1);          // 1: an implicit step that gave the film more energy than was done on it
                                           // gives the excess back from its velocities (energy_budget.h); 0: off
  int implicitSubsteps GB_DEFAULT(1);      // implicit steps per frame (a scene may ask for more; stability never does)
  float stabilitySafety GB_DEFAULT(0.5f);  // fraction of the explicit stability limit taken as the substep (0, 1]
  int maxSubsteps GB_DEFAULT(4000);        // refuse films whose stability limit needs more substeps per frame

  // --- Surface tension and elasticity (Section 5.1, Eqs. 3-4) ---
  float elasticityWeight GB_DEFAULT(12.5f);     // w_E, Table 2 [12.0, 13.0]; N/m, the stiffness scale of Eq. (4)
  float elasticityThickness GB_DEFAULT(4e-6f);  // k, "typically 4 um" (m)
  float gibbsFloorThickness GB_DEFAULT(0.0f);   // thinner film keeps Eq. (4)'s Gibbs elasticity at this thickness
                                                // (m); 0: the paper's formula all the way down. 1.5e-6 keeps the
                                                // thinnest film from being the softest (docs/model.md)
  float areaWeight GB_DEFAULT(0.035f);          // w_e, Table 2 [0.02, 0.05]; initial thickness is w_e x 100 um
  float marangoniLifetime GB_DEFAULT(0.2f);     // "life time < 10": ten paper steps of 0.02 s (s)
  float springPrestrain GB_DEFAULT(0.1f);       // springs rest this fraction shorter than at creation: taut film
  float springDamping GB_DEFAULT(0.0005f);      // k_d of Algorithm 1 (N s/m)
  float filmInertia GB_DEFAULT(0.1f);           // areal mass of the film used for its dynamics (kg/m^2)
  float airDrag GB_DEFAULT(0.1f);               // linear drag of still air on the film's velocity (Pa s/m)
  float gravityX GB_DEFAULT(0.0f);              // external force field g (m/s^2), world y is up
  float gravityY GB_DEFAULT(-9.81f);
  float gravityZ GB_DEFAULT(0.0f);

  // --- Air (Section 5.2, Eqs. 5-11) ---
  float airDirectionThreshold GB_DEFAULT(0.6f);   // lambda_air, Table 2 [0.5, 0.7] (cosine, dimensionless)
  float airInflowDistance GB_DEFAULT(1.0f);       // the "+ 1" of Eq. (5): distance at which the inflow halves (m)
  float airPressureGain GB_DEFAULT(10.0f);        // kappa: pressure per unit of normal air flow (Pa s/m^3)
  float pressureCoefficient GB_DEFAULT(1010.0f);  // P0 = 1.01 kPa, Eq. (11) (Pa)

  // --- Bursting and drainage (Section 6, Eqs. 14-15; Section 8) ---
  float thicknessThreshold GB_DEFAULT(35e-9f);  // lambda_thi, Table 2 [20, 50], read as nm (m)
  float sticky GB_DEFAULT(25.0f);               // Sticky, Table 2 [20, 30] (dimensionless)
  float drainageRate GB_DEFAULT(2.0f);  // rate of Eq. (15): liquid fraction sent per second per unit d_dir/Sticky (1/s)
  float surfaceTension GB_DEFAULT(0.025f);  // gamma of the soap solution, for the Taylor-Culick hole speed (N/m)
  float liquidDensity GB_DEFAULT(1000.0f);  // rho of the soap solution (kg/m^3)
  // Film flow (docs/model.md "Film flow"): the liquid flows over the film's surface, driven by gravity, Marangoni
  // stress and the air's shear, held by viscosity; it replaces Eqs. (14)-(15) unless filmFlow is 0.
  int filmFlow GB_DEFAULT(1);                    // 1: the thin-film flow; 0: the paper's drainage, Eqs. (14)-(15)
  float liquidViscosity GB_DEFAULT(1e-3f);       // mu of the soap solution (Pa s): water's
  float surfaceRigidity GB_DEFAULT(3e-4f);       // phi in [0, 1]: how far the surfaces hold the liquid back, the share
                                                 // of the Poiseuille friction 12 mu / e^2 it feels (1: immobile
                                                 // surfaces, lubrication; 0: plug flow)
  float flowViscosity GB_DEFAULT(2e-4f);         // nu_f, the flow's in-plane viscosity at the particles' scale (m^2/s)
  float airShear GB_DEFAULT(0.004f);             // k_air = mu_air / delta: shear stress of the air per speed of the air
                                                 // past the film, on each face (Pa s/m)
  float marangoniElasticity GB_DEFAULT(0.002f);  // E_M = -2 d(gamma)/d(ln Gamma): the surface tension's fall with the
                                                 // surfactant per area, both faces (N/m)
  float evaporationRate GB_DEFAULT(1.5e-7f);     // how fast the film thins by evaporation into the air, both faces
                                                 // (m/s; docs/model.md "Evaporation"); 0: saturated air
  float blackFilmThickness GB_DEFAULT(60e-9f);   // thinner film has turned black film: drawn without interference (m)
  int holeOpening GB_DEFAULT(0);           // 0: hole front at the Taylor-Culick speed; 1: one ring per frame (paper)
  float aerosolLifetime GB_DEFAULT(1.5f);  // aerosol droplets fade out over this time (s)
  float aerosolDrag GB_DEFAULT(2.0f);      // linear air drag rate on a droplet (1/s)
  float collisionThreshold GB_DEFAULT(1.75f);  // lambda_col, Table 2 [1.5, 2.0]: film Weber number of an impact
                                               // that bursts the film (collision.h); 0 turns it off
  float collisionDistance GB_DEFAULT(0.02f);   // film particles closer than this repel (self-collision) (m)
  float collisionStiffness GB_DEFAULT(1.0f);   // stiffness of that repulsion (N/m)
  float collisionDamping GB_DEFAULT(0.0002f);  // damping of the approach speed in a contact (N s/m)

  // --- Pinch-off ---
  float pinchDistance GB_DEFAULT(0.1f);  // wand tips closer than this close the film into a free bubble (m)
  float loopSwingRate GB_DEFAULT(6.0f);  // two wands: the fastest the hanging loop turns about the tips' span (rad/s),
                                         // about the swing of a 0.8 m string pendulum (wire_frame.h, swingLoop)

  // --- The performer's touch (cpu-reference/topology/body_touch.h) ---
  int touchWireFilm GB_DEFAULT(0);          // 1: the body touches the film on the wands too, not only free bubbles (the
                                            // wands' sticks, not modelled, otherwise keep it off the performer)
  int wetHands GB_DEFAULT(0);               // 1: the performer's hands are wet: the body pushes the film instead of
                                            // bursting it, and only a strike faster than touchStrikeSpeed bursts it
  float touchStrikeSpeed GB_DEFAULT(1.5f);  // how fast a wet hand must strike a film to burst it (m/s)
  float bubbleLift GB_DEFAULT(0.0f);        // the share of a free bubble's weight its air lifts: 1 floats it still
                                            // (neutrally buoyant, as --bubble-at places it), 0 lets it fall

  // --- Soap solution control (Section 7) ---
  float solution GB_DEFAULT(1.0f);               // remaining soap solution, 1 = full dip (0, 1]
  int particlesAtFullSolution GB_DEFAULT(9500);  // particles of a film made at solution 1.0 (Table 1: 9-10k)
  float solutionReserve GB_DEFAULT(5.0f);        // liquid a full dip leaves on the wire for new film, in films' worth
                                                 // (a soaked rope holds several: docs/model.md)
  float growthStretch GB_DEFAULT(1.15f);         // new film is drawn off the wire when the springs joining the wire
                                                 // to the film are this many times their rest length (mean)
  float yieldStretch GB_DEFAULT(1.3f);  // a spring stretched past this x its rest length yields: its rest grows with
                                        // it (new surface, the film thins); 0: the paper's purely elastic springs
  float yieldThickness GB_DEFAULT(0.5e-6f);    // film thinner than this no longer yields: too little liquid is left
                                               // to make new surface of, so a thinned region stays elastic (m)
  int energyNeutralContraction GB_DEFAULT(0);  // a free bubble's slack spring contracts: 0 to as taut as new film
                                               // (springPrestrain: the bubble rounds up, its spring energy grows);
                                               // 1 only as far as it was slack (the energy stays; docs/model.md)
  int mergeInterval GB_DEFAULT(8);  // a free bubble's crowded particles may merge on every this many frames (a merge
                                    // remakes the mesh and reloads the stepper; docs/model.md); 1: every frame
  int airTransfer GB_DEFAULT(1);    // 1: air flow transfer, Eqs. (7)-(8) (the paper); 0: each particle feels only
                                    // the inflow of Eq. (5) where it arrives (Figure 12a's comparison)

  // --- Physical surface tension (docs/model.md, "Tension models") ---
  int tensionModel GB_DEFAULT(0);           // 0: the paper's springs, Eq. (3); 1: physical, 2 gamma times the area
                                            // gradient (mean curvature), with the film's real mass
  float gibbsElasticity GB_DEFAULT(0.02f);  // E_G = 2 d(gamma)/d(ln A) of the film (N/m), physical model
};

#ifdef __cplusplus
}  // namespace gb
#endif
