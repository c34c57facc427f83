// The lowest eigenpairs of a closed triangle mesh's Laplace-Beltrami operator in its finite-element form,
//
//   -L phi = lambda M phi,
//
// L the cotangent Laplacian (cotan_laplacian.h; negative semidefinite, hence the minus) and M the lumped mass
// (mass_matrix.h). The generalized problem, not -L phi = lambda phi: with M the eigenvectors converge to the
// surface's own eigenfunctions as the mesh is refined, whatever its sampling, whereas the eigenvectors of L alone
// favour densely sampled regions (its Rayleigh quotient weighs each vertex alike, not each unit of area).
//
// Method: shift-and-invert Lanczos (Spectra's SymGEigsShiftSolver) on a sparse Cholesky factor of
// -L + s M, shift sigma = -s just below 0 (so the operator is positive definite and the pairs nearest 0, the
// lowest, converge first). Meshes of at most kDenseEigenVertexLimit vertices are solved densely instead (Eigen's
// GeneralizedSelfAdjointEigenSolver), where Lanczos would need more basis vectors than the mesh has vertices.
// Works on any closed manifold mesh, genus > 0 included; each connected component adds one zero eigenvalue.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>

#include "core/mesh/mesh.h"

namespace sd {

constexpr int kDenseEigenVertexLimit = 200;

struct EigenpairOptions {
  int count = 0;  // how many of the lowest pairs, the constant one (lambda = 0) included; 1 <= count < #V
  // Refuse (sd::Error naming the bytes) when the eigenvectors and the Lanczos basis would need more than this.
  std::size_t memory_budget_bytes = std::size_t(1) << 30;
  double tolerance = 1e-10;  // Spectra's relative tolerance on the Ritz values of the inverted operator
  int max_restarts = 1000;
  // Called now and then with an estimate of the fraction done (Lanczos has no known iteration count) and with 1
  // at the end; return false to cancel (throws sd::Error "eigen-decomposition cancelled").
  std::function<bool(double)> progress;
};

struct Eigenpairs {
  Eigen::VectorXd values;   // ascending; values[0] ~ 0 (the constant)
  Eigen::MatrixXd vectors;  // #V by count, M-orthonormal: vectors^T M vectors = I
  Eigen::VectorXd mass;     // M's diagonal
  int operations = 0;       // solves with the factor (Lanczos matrix-vector products)
  int restarts = 0;
  bool dense = false;    // solved by the dense fallback
  double factor_ms = 0;  // ordering and Cholesky factorization of -L + s M
  double solve_ms = 0;   // everything else
};

// Bytes the eigenvectors and the Lanczos basis take for `count` pairs on `vertices` vertices (the sparse factor,
// O(#V log #V) for a surface, is not included).
double eigenpair_memory_bytes(int vertices, int count);

// Throws sd::Error on a bad count, when over the memory budget, when cancelled, on a mesh whose Laplacian or
// mass matrix cannot be built, or when Lanczos does not converge.
Eigenpairs laplacian_eigenpairs(const Vertices& V, const Faces& F, const EigenpairOptions& options);

}  // namespace sd
