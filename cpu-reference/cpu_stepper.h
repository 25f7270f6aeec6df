#pragma once
// The CPU backend: one step is the list of stages of ARCHITECTURE.md, each run over all elements in
// parallel (OpenMP). The Vulkan stepper records the same list as dispatches.

#include "film.h"
#include "stages.h"

namespace gb {

class CpuStepper {
 public:
  // Advances the film by one substep. Returns the Boyle pressure used (Eq. 11; P_0 for an open film).
  float step(const Params& params, const StepUniforms& uniforms, Film& film);

  // Geometry (normals, Voronoi areas) and the film state from the current positions, without stepping:
  // what a step's first stages compute, for diagnostics and the stability bound.
  void refreshGeometry(const Params& params, Film& film);

  // Enclosed (closed film) or swept (open film, cone to the origin) volume with the fixed-shape tree sum.
  float volume(const Film& film, const Vec3& origin);

 private:
  std::vector<float> triangleVolumes_;  // scratch for the volume reduction, reused every step
};

}  // namespace gb
