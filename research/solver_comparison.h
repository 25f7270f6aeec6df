#pragma once
// Candidate solvers for the implicit step's objective (implicit_euler.h), built on the CPU to
// measure the choice of vertex block descent against them (bench/solver_bench.cpp, docs/model.md
// "Integrators"). All of them use the particles' 3x3 blocks of objectiveBlock, so they solve the same
// objective with the same projected Hessian:
//   - vertex block descent (VBD) as the step runs it: Gauss-Seidel over the colours, a trust-region Newton
//     step per particle;
//   - VBD with Chebyshev acceleration (Chen et al. 2024, after Wang 2015): after sweep k the
//     iterate is x_k = omega_k (xbar_k - x_{k-2}) + x_{k-2}, omega_1 = 1, omega_2 = 2 / (2 - rho^2),
//     omega_k = 4 / (4 - rho^2 omega_{k-1}), rho the spectral radius of the plain sweep;
//   - block Jacobi on the same blocks (every particle's step from the same iterate: the projective-dynamics
//     gather of Wang 2015 on this objective, which has no constant system matrix), with the same Chebyshev
//     weights and an under-relaxation of each step;
//   - Newton's method whose linear system (the projected Hessian H, the sum of the blocks' springs and
//     triangles) is solved by conjugate gradients, matrix-free (H p gathered over each particle's one-ring from
//     the positions of the Newton step's start), preconditioned by the inverse 3x3 diagonal blocks: Baraff and
//     Witkin (1998) take one such Newton step per frame.
// Open films only: a closed bubble's Boyle term needs the enclosed volume at every iterate.

#include <string>
#include <vector>

#include "model/film.h"
#include "solver/implicit_euler.h"

namespace gb {

enum class SolverKind { VertexBlockDescent, Jacobi, NewtonPcg };

struct SolverChoice {
  SolverKind kind = SolverKind::VertexBlockDescent;
  float rho = 0.0f;         // VBD and Jacobi: Chebyshev's spectral radius estimate; 0 turns acceleration off
  float relaxation = 1.0f;  // Jacobi: the fraction of each particle's Newton step taken, (0, 1]
  int cgPerNewton = 10;     // Newton-PCG: conjugate-gradient iterations per Newton step
};
std::string describe(const SolverChoice& choice);  // e.g. "Chebyshev VBD, rho 0.9"

// The step's objective (J) at the film's positions, in double: inertia m/(2h^2) |x - y|^2, the springs'
// energy (or 2 gamma x area), the contact penalty, and the dissipations (spring and contact damping, drag, air
// coupling) in the displacement over the step; terms that hold no solved particle are left out. The damping
// terms take the spring direction at the iterate, whose own derivative objectiveBlock's gradient leaves out
// (c/h = 0.025 N/m against springs of several N/m with the defaults). Throws std::invalid_argument for a closed
// film.
double implicitObjective(const Params& p, const StepUniforms& u, const Topology& topo, const State& s);

// One step's solve on a film that the step's stages have brought up to implicit_predict (x_t kept, the wire
// placed, the first guess made), one iteration at a time. The iterate is always the film's positions.
class ImplicitSolve {
 public:
  ImplicitSolve(const Params& p, const StepUniforms& u, Film& film, SolverChoice choice);
  // One sweep (VBD), one Jacobi pass, or one conjugate-gradient iteration (Newton-PCG: a new Newton step
  // starts every cgPerNewton iterations, and the film holds the Newton step's start plus the step found so far).
  void iterate();
  [[nodiscard]] int iterations() const { return iterations_; }

 private:
  void chebyshev(const Vec3Array& beforeSweep);
  void vbdSweep();
  void jacobiPass();
  void startNewton();
  void conjugateGradientIteration();
  void hessianProduct(const Vec3Array& v, Vec3Array& out) const;

  Params params_;
  StepUniforms uniforms_;
  Film& film_;
  SolverChoice choice_;
  std::vector<uint32_t> solved_;  // the particles the solver moves (the colouring's living ones), in colour order
  int iterations_ = 0;
  float omega_ = 1.0f;
  Vec3Array older_;  // Chebyshev: x_{k-2}
  Vec3Array step_;   // Jacobi: every particle's step from the same iterate
  // Newton-PCG, in the particles' indices (zero for those not solved):
  std::vector<VertexBlock> blocks_;  // at the Newton step's start: gradient, diagonal block, trust scale
  Vec3Array start_;                  // positions at the Newton step's start (H is taken there)
  Vec3Array delta_, residual_, direction_, preconditioned_, product_;
  double residualDot_ = 0;  // r . z
};

}  // namespace gb
