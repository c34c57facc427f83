#include "core/mesh/laplacian_eigenpairs.h"

#include <Spectra/SymGEigsShiftSolver.h>
#include <Spectra/Util/Version.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/mesh/cotan_laplacian.h"
#include "core/mesh/mass_matrix.h"
#include "core/timer.h"

static_assert(SPECTRA_VERSION >= 10000, "Spectra 1.0 or newer is required (Debian libspectra-dev)");

namespace sd {
namespace {

// Lanczos basis size: Spectra advises at least twice the number of pairs; 20 more for few pairs.
int lanczos_size(int vertices, int count) { return std::min(vertices, std::max(2 * count + 1, count + 20)); }

// Reports progress (throttled to steps of 1%) and turns a refusal into the cancellation error.
class Progress {
 public:
  explicit Progress(const std::function<bool(double)>& callback) : callback_(callback) {}
  void report(double fraction, bool force = false) {
    if (!callback_ || (!force && fraction < last_ + 0.01)) return;
    last_ = fraction;
    if (!callback_(fraction)) throw Error(ErrorCode::Cancelled, "eigen-decomposition cancelled");
  }

 private:
  const std::function<bool(double)>& callback_;
  double last_ = -1.0;
};

// y = M x for the diagonal M (Spectra's B operator, also its inner product).
class DiagonalProduct {
 public:
  using Scalar = double;
  explicit DiagonalProduct(const Eigen::VectorXd& diagonal) : d_(diagonal) {}
  Eigen::Index rows() const { return d_.size(); }
  Eigen::Index cols() const { return d_.size(); }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, d_.size()) = d_.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(x, d_.size()));
  }

 private:
  const Eigen::VectorXd& d_;
};

// y = (K - sigma M)^-1 x by a sparse Cholesky factor, K = -L positive semidefinite and sigma < 0 so that K -
// sigma M is positive definite. Counts its solves and reports progress from them (Spectra calls set_shift once,
// then perform_op for every Lanczos vector).
class ShiftInvert {
 public:
  using Scalar = double;
  ShiftInvert(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass, int basis_size, Progress& progress)
      : K_(K), mass_(mass), basis_size_(basis_size), progress_(progress) {}
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void set_shift(double sigma) {
    const double t0 = now_ms();
    Eigen::SparseMatrix<double> A = K_;
    for (Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) -= sigma * mass_[i];  // diagonal in the pattern
    factor_.compute(A);
    if (factor_.info() != Eigen::Success)
      throw Error(ErrorCode::NumericalFailure,
                  "eigen-decomposition: -L + s M could not be factored (is the mesh closed and free of degenerate "
                  "triangles?)");
    factor_ms_ = now_ms() - t0;
  }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, K_.rows()) = factor_.solve(Eigen::Map<const Eigen::VectorXd>(x, K_.rows()));
    ++operations_;
    // Lanczos usually converges within a few basis sizes of solves: an estimate, not a count.
    progress_.report(0.1 + 0.85 * (1.0 - std::exp(-double(operations_) / (2.0 * basis_size_))));
  }
  int operations() const { return operations_; }
  double factor_ms() const { return factor_ms_; }

 private:
  const Eigen::SparseMatrix<double>& K_;
  const Eigen::VectorXd& mass_;
  int basis_size_;
  Progress& progress_;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> factor_;
  mutable int operations_ = 0;
  double factor_ms_ = 0;
};

void solve_dense(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass, int count, Eigenpairs& out) {
  const Eigen::MatrixXd M = mass.asDiagonal();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(K), M);
  if (eig.info() != Eigen::Success)
    throw Error(ErrorCode::NumericalFailure, "eigen-decomposition: the dense eigensolver failed");
  out.values = eig.eigenvalues().head(count);  // ascending, vectors M-normalised
  out.vectors = eig.eigenvectors().leftCols(count);
  out.dense = true;
}

void solve_lanczos(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass, const EigenpairOptions& options,
                   Progress& progress, Eigenpairs& out) {
  const int n = static_cast<int>(K.rows()), count = options.count;
  const int basis = lanczos_size(n, count);
  // Shift just below 0 in units of the first non-zero eigenvalue's typical size: with M normalised to unit total
  // area (mass sums to 1) the eigenvalues are dimensionless, about 4 pi j for the j-th (Weyl), at least ~1.
  const double sigma = -1.0;
  DiagonalProduct B(mass);
  ShiftInvert op(K, mass, basis, progress);
  using Solver = Spectra::SymGEigsShiftSolver<ShiftInvert, DiagonalProduct, Spectra::GEigsMode::ShiftInvert>;
  Solver solver(op, B, count, basis, sigma);  // factors -L - sigma M
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, options.max_restarts, options.tolerance,
                 Spectra::SortRule::SmallestAlge);
  if (solver.info() != Spectra::CompInfo::Successful) {
    std::ostringstream message;
    message << "eigen-decomposition: Lanczos did not converge for " << count << " eigenpairs within "
            << options.max_restarts << " restarts (" << op.operations() << " solves)";
    throw Error(ErrorCode::NumericalFailure, message.str());
  }
  out.values = solver.eigenvalues();
  out.vectors = solver.eigenvectors();
  out.operations = op.operations();
  out.restarts = static_cast<int>(solver.num_iterations());
  out.factor_ms = op.factor_ms();
}

}  // namespace

double eigenpair_memory_bytes(int vertices, int count) {
  const double basis = lanczos_size(vertices, count);
  return 8.0 * double(vertices) * (double(count) + basis) + 8.0 * basis * basis;
}

Eigenpairs laplacian_eigenpairs(const Vertices& V, const Faces& F, const EigenpairOptions& options) {
  const double t0 = now_ms();
  const int n = static_cast<int>(V.rows());
  if (options.count < 1 || options.count >= n)
    throw Error("eigen-decomposition: the number of eigenpairs must be from 1 to " + std::to_string(n - 1) +
                " (the mesh has " + std::to_string(n) + " vertices); got " + std::to_string(options.count));
  const double bytes = eigenpair_memory_bytes(n, options.count);
  if (bytes > double(options.memory_budget_bytes)) {
    std::ostringstream message;
    message << "eigen-decomposition: " << options.count << " eigenvectors of a " << n << "-vertex mesh need about "
            << std::setprecision(3) << bytes / 1e6
            << " MB (eigenvectors and the Lanczos basis), more than the budget of "
            << double(options.memory_budget_bytes) / 1e6 << " MB; use fewer modes";
    throw Error(ErrorCode::MemoryBudget, message.str());
  }
  Progress progress(options.progress);
  progress.report(0.0, true);
  Eigenpairs out;
  const Eigen::SparseMatrix<double> K = -cotan_laplacian(V, F);
  const Eigen::VectorXd mass = lumped_mass(V, F);
  // Solve with the mass normalised to unit total area (scale-free shift and tolerances), then scale back:
  // lambda = lambda_hat / area, phi = phi_hat / sqrt(area).
  const double area = mass.sum();
  const Eigen::VectorXd unit_mass = mass / area;
  if (n <= kDenseEigenVertexLimit) solve_dense(K, unit_mass, options.count, out);
  else solve_lanczos(K, unit_mass, options, progress, out);
  out.values /= area;
  out.vectors /= std::sqrt(area);
  out.mass = mass;
  out.solve_ms = now_ms() - t0 - out.factor_ms;
  progress.report(1.0, true);
  return out;
}

}  // namespace sd
