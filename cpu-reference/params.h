#pragma once
// Every model parameter of the paper (Table 2 and Sections 5-7) in one struct, in SI units.
// The paper's own symbol is in the comment; docs/model.md gives the mapping from the paper's scale to SI
// and the reason for each default. Plain floats and ints only: the Vulkan backend mirrors this block.

#include <string>
#include <vector>

namespace gb {

struct Params {
  // --- Time integration (Section 5.3) ---
  float frameTime = 0.02f;        // h, Table 2: 0.02 s. One frame of wand input; split into stable substeps.
  float stabilitySafety = 0.5f;   // fraction of the explicit stability limit taken as the substep (0, 1]
  int maxSubsteps = 4000;         // refuse films whose stability limit would need more substeps per frame

  // --- Surface tension and elasticity (Section 5.1, Eqs. 3-4) ---
  float elasticityWeight = 12.5f;     // w_E, Table 2 [12.0, 13.0]; N/m, the stiffness scale of Eq. (4)
  float elasticityThickness = 4e-6f;  // k, "typically 4 um" (m)
  float areaWeight = 0.035f;          // w_e, Table 2 [0.02, 0.05]; initial thickness e0 = w_e * 100 um
  float marangoniLifetime = 0.2f;     // "life time < 10": ten paper steps of h = 0.02 s (s)
  float springPrestrain = 0.1f;       // springs rest this fraction shorter than at creation: a film is taut
  float springDamping = 0.0005f;      // k_d of Algorithm 1 (N s/m)
  float filmInertia = 0.1f;           // areal mass of the film used for its dynamics (kg/m^2)
  float airDrag = 0.1f;               // linear drag of still air on the film's velocity (Pa s/m)
  float gravityX = 0.0f;              // external force field g (m/s^2), world y is up
  float gravityY = -9.81f;
  float gravityZ = 0.0f;

  // --- Air (Section 5.2, Eqs. 5-11) ---
  float airDirectionThreshold = 0.6f;  // lambda_air, Table 2 [0.5, 0.7] (cosine, dimensionless)
  float airInflowDistance = 1.0f;      // the "+ 1" of Eq. (5): distance at which the inflow halves (m)
  float airPressureGain = 10.0f;       // kappa: pressure on the film per unit of normal air flow (Pa s/m^3)
  float pressureCoefficient = 1010.0f;  // P0 = 1.01 kPa, Eq. (11) (Pa)

  // --- Bursting and drainage (Section 6, Eqs. 14-15; Section 8) ---
  float thicknessThreshold = 35e-9f;  // lambda_thi, Table 2 [20, 50], read as nm (m)
  float sticky = 25.0f;               // Sticky, Table 2 [20, 30] (dimensionless)
  float collisionThreshold = 1.75f;   // lambda_col, Table 2 [1.5, 2.0], read as impact speed (m/s)

  // --- Soap solution control (Section 7) ---
  float solution = 1.0f;              // remaining soap solution, 1 = full dip (0, 1]
  int particlesAtFullSolution = 9500;  // particles of a film made at solution 1.0 (Table 1: 9-10k)

  // Initial film thickness e0 (m): the paper's area weight read as liquid per rest area.
  [[nodiscard]] float initialThickness() const { return areaWeight * 100e-6f; }
};

// One message per parameter that is out of its valid range, each naming the parameter, its value and the
// range. Empty when the parameters are usable.
std::vector<std::string> validate(const Params& params);

}  // namespace gb
