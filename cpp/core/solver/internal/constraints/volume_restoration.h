// Putting an iterate back on the hard constraints (hard_constraints.h: the volume's, the skeleton's) after a
// line-search step (docs/method.md section 8: keep the hard constraint hard): X moves along the step solver's restoring
// directions r_k (W N^-1 c_k, one per constraint) by the coefficients t that make g(X + R t) = 0.
//   K = 1 (the global volume): psi(X + t r) is a cubic in t; its four coefficients take one pass over the
//         triangles (volume_along), and scalar Newton then runs on four numbers.
//   otherwise (volume parts, a skeleton): Newton on the K constraints, t <- t - (G^T R)^-1 g with G their
//         gradients at X + R t (K by K system; one evaluation and one gradient pass per step).
// Either way a Newton step that does not reduce the residual ends the iteration (the step is kept as it was).
#pragma once

#include <Eigen/Core>

#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/constraints/hard_constraints.h"
#include "core/solver/internal/constraints/restoring_directions.h"

namespace sd {

// Moves X (and U) along the directions (their images dx, #V by 3D, and du, m by 3D) with up to `max_newton` Newton
// steps, driving their `driven` constraints (every one when empty) to zero. Returns the error left, relative:
// (psi(X) - psi(X0)) / psi(X0) for the global volume alone, else the largest |g_k| / scale_k over every constraint
// (HardConstraints::relative_error). points and values: the skeleton's points and the constraints' values g at X,
// when the caller has evaluated them (empty: computed, a pass over the mesh each).
double restore_constraints(const HardConstraints& hard, const DeformationEnergy& energy, Vertices& X,
                           Eigen::MatrixXd& U, const RestoringDirections& directions, int max_newton = 3,
                           const Eigen::MatrixXd& points = Eigen::MatrixXd(),
                           const Eigen::VectorXd& values = Eigen::VectorXd());

}  // namespace sd
