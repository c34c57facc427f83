#include "core/basis/spectral_basis.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/mesh/laplacian_eigenpairs.h"
#include "core/timer.h"

namespace sd {
namespace {

// A column whose remainder after the earlier columns has less than this fraction of its squared norm is
// dependent on them (relative remainder 1e-5).
constexpr double kDependentFraction = 1e-10;

// Columns [1, x, y, z, phi_0 .. phi_k], the coordinates centred and scaled to unit size so that the Gram matrix
// is well conditioned wherever the model sits (the span is the same).
Eigen::MatrixXd raw_columns(const Vertices& X0, const Eigen::MatrixXd& eigenvectors) {
  const Eigen::Index n = X0.rows();
  Eigen::MatrixXd Q(n, 4 + eigenvectors.cols());
  Q.col(0).setOnes();
  const Eigen::RowVector3d centre = X0.colwise().mean();
  const double size = std::max(bounding_box_diagonal(X0), 1e-300);
  Q.middleCols(1, 3) = (X0.rowwise() - centre) / size;
  Q.rightCols(eigenvectors.cols()) = eigenvectors;
  return Q;
}

// Orthonormalises the columns of Q in <f, g> = f^T diag(w) g, in order, leaving out those dependent on the
// earlier ones (Cholesky QR of the Gram matrix with dropping, then one more Cholesky QR pass for accuracy).
// Returns the indices of the columns kept.
std::vector<int> orthonormalize(Eigen::MatrixXd& Q, const Eigen::VectorXd& w) {
  const Eigen::Index p = Q.cols();
  const Eigen::MatrixXd G = Q.transpose() * w.asDiagonal() * Q;
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(p, p);
  std::vector<int> kept;
  for (Eigen::Index j = 0; j < p; ++j) {
    double remainder = G(j, j);
    for (size_t a = 0; a < kept.size(); ++a) {
      const int i = kept[a];
      double r = G(i, j);
      for (size_t b = 0; b < a; ++b) r -= R(kept[b], i) * R(kept[b], j);
      R(i, j) = r / R(i, i);
      remainder -= R(i, j) * R(i, j);
    }
    if (!(remainder > kDependentFraction * G(j, j))) continue;
    R(j, j) = std::sqrt(remainder);
    kept.push_back(static_cast<int>(j));
  }
  const Eigen::Index q = static_cast<Eigen::Index>(kept.size());
  Eigen::MatrixXd Qk(Q.rows(), q), Rk(q, q);
  for (Eigen::Index a = 0; a < q; ++a) {
    Qk.col(a) = Q.col(kept[a]);
    for (Eigen::Index b = 0; b < q; ++b) Rk(a, b) = R(kept[a], kept[b]);
  }
  Rk.triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(Qk);
  // Second pass: the first leaves errors of about cond^2 * eps in the Gram matrix; this one removes them.
  const Eigen::MatrixXd G2 = Qk.transpose() * w.asDiagonal() * Qk;
  const Eigen::LLT<Eigen::MatrixXd> llt(G2);
  if (llt.info() != Eigen::Success)
    throw Error(ErrorCode::NumericalFailure, "spectral basis: the columns could not be orthonormalised");
  llt.matrixU().solveInPlace<Eigen::OnTheRight>(Qk);
  Q = std::move(Qk);
  return kept;
}

}  // namespace

double spectral_basis_memory_bytes(int vertices, int modes) {
  // The eigenpairs, then the raw columns and B (float64 while it is made).
  return eigenpair_memory_bytes(vertices, modes + 1) + 2.0 * 8.0 * double(vertices) * double(modes + 5);
}

SpectralBasis spectral_basis(const Mesh& mesh, const SpectralOptions& options) {
  const int n = static_cast<int>(mesh.V.rows()), k = options.modes;
  // Counted after welding (the solver's points), which a file's vertex count can hide.
  if (n < 6)
    throw Error(
        "spectral basis: needs a mesh of at least 6 vertices (B has modes + 4 columns, modes >= 1); this one "
        "has " +
        std::to_string(n) + " distinct points");
  if (k < 1 || k > n - 5)  // not k + 5 > n, which overflows for k near INT_MAX
    throw Error("spectral basis: the number of modes must be from 1 to " + std::to_string(std::max(n - 5, 0)) +
                " for this mesh of " + std::to_string(n) + " vertices (B has modes + 4 columns); got " +
                std::to_string(k));
  const double bytes = spectral_basis_memory_bytes(n, k);
  if (bytes > double(options.memory_budget_bytes)) {
    std::ostringstream message;
    message << "spectral basis: " << k << " modes on " << n << " vertices need about " << std::setprecision(3)
            << bytes / 1e6 << " MB (eigenvectors, the Lanczos basis and B), more than the budget of "
            << double(options.memory_budget_bytes) / 1e6 << " MB; use fewer modes";
    throw Error(ErrorCode::MemoryBudget, message.str());
  }
  const double t0 = now_ms();
  EigenpairOptions eigen;
  eigen.count = k + 1;
  eigen.memory_budget_bytes = options.memory_budget_bytes;
  if (options.progress) eigen.progress = [&](double f) { return options.progress(0.9 * f); };
  const Eigenpairs pairs = laplacian_eigenpairs(mesh.V, mesh.F, eigen);
  SpectralBasis out;
  out.eigenvalues = pairs.values;
  out.operations = pairs.operations;
  out.eigen_ms = now_ms() - t0;

  const double t1 = now_ms();
  Eigen::MatrixXd Q = raw_columns(mesh.V, pairs.vectors);
  const Eigen::VectorXd w = pairs.mass / pairs.mass.sum();
  const std::vector<int> kept = orthonormalize(Q, w);
  // The constant eigenvector (or, with several components, one combination of the zero modes) always goes.
  out.dropped = (k + 5) - static_cast<int>(kept.size()) - 1;
  for (int j = 0; j < 4; ++j)
    if (j >= static_cast<int>(kept.size()) || kept[j] != j)
      throw Error(ErrorCode::InvalidMesh,
                  "spectral basis: the mesh's coordinates are linearly dependent (is it flat?)");
  out.rest_coefficients = Q.transpose() * w.asDiagonal() * mesh.V;  // exact: X0 is in the span
  out.B = BasisMatrix(n, static_cast<int>(Q.cols()), options.single_precision);
  for (int i = 0; i < n; ++i) out.B.set_row(i, Q.row(i));
  out.orthonormalize_ms = now_ms() - t1;
  if (options.progress && !options.progress(1.0)) throw Error(ErrorCode::Cancelled, "eigen-decomposition cancelled");
  return out;
}

}  // namespace sd
