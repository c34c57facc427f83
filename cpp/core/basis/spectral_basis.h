// A subspace without a cage, from the mesh's own low frequencies (docs/method.md section 15; the future work
// of the project report the project started from: deformations that keep surface detail live in the span of
// the Laplacian's low modes):
//
//   B = [1, x0, y0, z0, phi_1 .. phi_k]   (#V by k + 4)
//
// the constant, the rest coordinates and the k lowest non-trivial eigenvectors of -L phi = lambda M phi
// (laplacian_eigenpairs.h: the generalized problem with the lumped mass, so the modes follow the surface, not its
// sampling). The columns are then made orthonormal in the area-weighted inner product <f, g> = f^T M g / area
// (B^T (M / area) B = I; the constant column stays 1): the span, which is all the solver sees, is unchanged, but
// the coefficients are well scaled whatever the model's units and position.
//
// X = B C takes the place of the cage's X = W P everywhere in the solver (steps, preconditioner, volume,
// restoration, line search). The rest pose and every affine map of it lie in the span exactly (X0 = B C0), so,
// as with the cage's linear precision, the rest pose is a minimizer and rigid motions of the handles are
// reproduced exactly.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>

#include "core/mesh/mesh.h"
#include "core/basis/basis_matrix.h"

namespace sd {

struct SpectralOptions {
  int modes = 0;                  // k >= 1 (the mesh needs at least k + 5 vertices)
  bool single_precision = false;  // store B in float32 (as MvcOptions::single_precision)
  // Refuse (sd::Error naming the bytes) when the eigenvectors, the Lanczos basis and B would need more.
  std::size_t memory_budget_bytes = std::size_t(1) << 30;
  // Fraction done (an estimate while Lanczos runs), 1 at the end; return false to cancel (sd::Error).
  std::function<bool(double)> progress;
};

struct SpectralBasis {
  BasisMatrix B;                      // #V by k + 4, columns orthonormal in M / area
  Eigen::MatrixXd rest_coefficients;  // C0, (k + 4) by 3: B C0 = X0
  Eigen::VectorXd eigenvalues;        // lambda_0 ~ 0 (the constant) .. lambda_k, ascending
  // Eigenvectors numerically in the span of the columns before them (relative remainder below 1e-5) are left
  // out. The constant eigenvector always is, and is not counted; each other one counted here makes B one column
  // narrower than k + 4. (With several connected components, the other zero modes are kept: they move the
  // components apart.)
  int dropped = 0;
  int operations = 0;   // Lanczos solves
  double eigen_ms = 0;  // eigen-decomposition (factorization included)
  double orthonormalize_ms = 0;
};

// Bytes spectral_basis needs for k modes on #V vertices (refused above options.memory_budget_bytes).
double spectral_basis_memory_bytes(int vertices, int modes);

// Throws sd::Error on too few vertices for k modes, over the memory budget, when cancelled, or when the
// eigen-decomposition fails (see laplacian_eigenpairs).
SpectralBasis spectral_basis(const Mesh& mesh, const SpectralOptions& options);

}  // namespace sd
