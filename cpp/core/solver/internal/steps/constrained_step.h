// One Gauss-Newton step with Lagrange multipliers for the hard constraints (docs/method.md section 6;
// hard_constraints.h: the volume's and the skeleton's), in whatever unknowns a step solver uses (cage vertices P
// with X = W P, or X itself).
//
// K constraints: the global volume (K = 1, g = psi(X) - psi(X0)) or one per volume part (g_k = V_k(X) -
// V_k(X0), part_volume.h). With A = (J_f W)^T (J_f W), b = W^T J_f^T f and C = [c_1 .. c_K], c_k = W^T grad g_k,
// the step minimizes 1/2 |f + J_f W h|^2 subject to g + C^T h = 0:
//   u = A^-1 b,  V = A^-1 C,  S = C^T V (K by K, the Schur complement),
//   lambda = S^-1 (g - C^T u),  h = -(u + V lambda).
// With K = 1 that is lambda = (g - c.u) / (c.v). (Derivations that write the same h with
// lambda = -(c.v)^-1 (g - c.u) have the opposite sign; with h = -A^-1 (b + lambda c) only this sign satisfies the
// linearized constraint c.h = -g, which the tests check.)
// The merit of the line search is 1/2 |f|^2 + lambda . g; its slope along h is h.(b + C lambda).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>

#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/constraints/restoring_directions.h"
#include "core/solver/solver_types.h"

namespace sd {

struct ConstrainedStep {
  Eigen::MatrixXd du;  // step of the unknowns (m by 3, or #V by 3 in the full space)
  Eigen::MatrixXd dx;  // its image in X space, #V by 3
  // The directions restoration puts a trial back on the hard constraints along: one per constraint (m by 3K of
  // the unknowns and their #V by 3K images; empty without hard constraints).
  RestoringDirections restore;
  Eigen::VectorXd lambda;  // K multipliers (zeros with volume off)
  double slope = 0;        // d/d alpha merit(X + alpha dx) at 0 = du.(b + C lambda); < 0 for descent
  int inner_iterations = 0;
  int products = 0;
  int passes = 0;
  int fallbacks = 0;
  // Made with constraint gradients from an earlier point (a drag's frame, ReducedSubspace::volume_directions): its
  // slope and lambda are the model's, not the true merit's, so the Gauss-Newton loop never stops on it and, where it
  // cannot be taken, makes the step again at the same targets (with fresh gradients).
  bool lagged = false;
};

// Computes constrained Gauss-Newton steps for one choice of unknowns.
class StepSolver {
 public:
  virtual ~StepSolver() = default;
  // Re-factors what depends on the handle set and the position weight (the constant preconditioner).
  // Throws sd::Error when it is singular; the solver is then unchanged.
  virtual void refactor(const DeformationEnergy& energy) = 0;
  // The step at X (unknowns U), where J and e were computed. Throws sd::Error on a singular system.
  virtual ConstrainedStep compute(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                                  const Eigen::MatrixXd& U, const SolverOptions& options) = 0;
  // A regularisation of the unknowns that the step's problem adds to the energy (the cage subspace's,
  // cage_regularization.h): part of the merit the line search compares. 0 unless overridden.
  virtual double regularization_energy(const Eigen::MatrixXd& /*U*/) const { return 0.0; }
  // Drops what earlier steps taught the solver (the fast subspace preconditioner's pairs), so a solve after
  // a reset does not depend on what came before it.
  virtual void forget_history() {}
  // The skeleton's points at unknowns U, where the step's space maps them more cheaply than the mesh does (the
  // subspace: O(m #points) against O(#V #points)); nothing to have the energy map them from X.
  virtual std::optional<Eigen::MatrixXd> skeleton_points(const Eigen::MatrixXd& /*U*/) { return std::nullopt; }
};

// x = S^-1 rhs for a K by K Schur complement S = C^T A^-1 C (A named `matrix` in the message): a division
// when K = 1, else LDLT. Throws sd::Error when S is not positive definite: the volume gradient(s) leave the
// space of the step, or (K > 1) the parts' gradients are linearly dependent in it.
Eigen::VectorXd solve_schur(const Eigen::MatrixXd& S, const Eigen::VectorXd& rhs, const char* matrix);

// The multipliers lambda = S^-1 (g - C^T u), S = C^T V, for V = A^-1 C (blocks of 3 columns per constraint).
Eigen::VectorXd volume_multipliers(const Eigen::MatrixXd& u, const Eigen::MatrixXd& V, const Eigen::MatrixXd& C,
                                   const Eigen::VectorXd& g);

// C^T Z for blocks (K by s for C m by 3K, Z m by 3s): entry (k, t) = c_k . z_t.
Eigen::MatrixXd block_products(const Eigen::MatrixXd& C, const Eigen::MatrixXd& Z);

// a + sum_k x_k B_k over the 3-column blocks of B (b + C lambda, u + V lambda).
Eigen::MatrixXd add_blocks(const Eigen::MatrixXd& a, const Eigen::MatrixXd& B, const Eigen::VectorXd& x);

// lambda . g, accumulated from the first product (so K = 1 is exactly lambda g); 0 for no constraints.
double multiplier_dot(const Eigen::VectorXd& lambda, const Eigen::VectorXd& g);

// Relative constraint error |g_k| / scale_k (hard_constraints.h) below which the fast steps start their projected
// PCG at h = 0 instead of on C^T h = -g (which costs products): restoration after each accepted step leaves ~1e-15.
constexpr double kNegligibleVolumeError = 1e-12;
// g itself, or zeros when every entry is negligible in that sense.
Eigen::VectorXd start_constraint(const Eigen::VectorXd& g, const Eigen::VectorXd& scales);

}  // namespace sd
