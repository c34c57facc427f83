// One Gauss-Newton step with a Lagrange multiplier for the volume constraint (docs/method.md section 6), in
// whatever unknowns a step solver uses (cage vertices P with X = W P, or X itself).
//
// With A = (J_f W)^T (J_f W), b = W^T J_f^T f, c = W^T grad psi and g = psi(X) - psi(X0), the step
// minimizes 1/2 |f + J_f W h|^2 subject to g + c.h = 0:
//   u = A^-1 b,  v = A^-1 c,  lambda = (g - c.u) / (c.v),  h = -(u + lambda v).
// (Derivations that write the same h with lambda = -(c.v)^-1 (g - c.u) have the opposite sign; with
// h = -A^-1 (b + lambda c) only this sign satisfies the linearized constraint c.h = -g, which the tests check.)
// The merit of the line search is 1/2 |f|^2 + lambda g; its slope along h is h.(b + lambda c).
#pragma once

#include <Eigen/Core>

#include "core/solver/internal/deformation_energy.h"
#include "core/solver/solver_types.h"

namespace sd {

struct ConstrainedStep {
  Eigen::MatrixXd du;          // step of the unknowns (m by 3, or #V by 3 in the full space)
  Eigen::MatrixXd dx;          // its image in X space, #V by 3
  Eigen::MatrixXd restore_du;  // volume-restoration direction of the unknowns (empty with volume off)
  Eigen::MatrixXd restore_dx;  // its image, #V by 3
  double lambda = 0;
  double slope = 0;            // d/d alpha merit(X + alpha dx) at 0 = du.(b + lambda c); < 0 for descent
  int inner_iterations = 0;
  int products = 0;
  int passes = 0;
  int fallbacks = 0;
};

// Computes constrained Gauss-Newton steps for one choice of unknowns.
class StepSolver {
 public:
  virtual ~StepSolver() = default;
  // Re-factors what depends on the handle set and the position weight (the constant preconditioner).
  // Throws sd::Error when it is singular; the solver is then unchanged.
  virtual void refactor(const DeformationEnergy& energy) = 0;
  // The step at X, where J and e were computed. Throws sd::Error on a singular system.
  virtual ConstrainedStep compute(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                                  const SolverOptions& options) = 0;
  // Drops what earlier steps taught the solver (the fast subspace preconditioner's pairs), so a solve after
  // a reset does not depend on what came before it.
  virtual void forget_history() {}
};

// lambda = (g - c.u) / (c.v) (0 when volume is off, v empty). Throws sd::Error when c.v is not positive
// (the volume gradient has no component the step can follow).
double volume_multiplier(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, const Eigen::MatrixXd& c, double g);

// Relative volume error |g| / psi0 below which the fast steps start their projected PCG at h = 0 instead of
// on c.h = -g (which costs a product): restoration after each accepted step leaves ~1e-15.
constexpr double kNegligibleVolumeError = 1e-12;

}  // namespace sd
