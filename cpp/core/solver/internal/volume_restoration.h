// Putting an iterate back on the volume constraints after a line-search step (docs/method.md section 8: keep the hard
// constraint hard): X moves along the step solver's restoring directions r_k (W N^-1 c_k, one per constraint)
// by the coefficients t that make g(X + R t) = 0.
//   K = 1 (the global volume): psi(X + t r) is a cubic in t; its four coefficients take one pass over the
//         triangles (volume_along), and scalar Newton then runs on four numbers.
//   K > 1 (volume parts): Newton on the K part volumes, t <- t - (G^T R)^-1 g with G the part volumes'
//         gradients at X + R t (K by K system; one evaluation and one gradient pass per step).
// Either way a Newton step that does not reduce the residual ends the iteration (the step is kept as it was).
#pragma once

#include <Eigen/Core>

#include "core/solver/internal/deformation_energy.h"

namespace sd {

// Moves X (and U) along (restore_dx, restore_du) (#V by 3K, m by 3K) with up to `max_newton` Newton steps.
// Returns the volume error left relative to the rest volume: (psi(X) - psi(X0)) / psi(X0) for K = 1, the
// largest |g_k| / psi(X0) for K > 1.
double restore_volume(const DeformationEnergy& energy, Vertices& X, Eigen::MatrixXd& U,
                      const Eigen::MatrixXd& restore_dx, const Eigen::MatrixXd& restore_du, int max_newton = 3);

}  // namespace sd
