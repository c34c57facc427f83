#include "core/solver/internal/steps/step_conditioning.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/MatOp/SparseSymShiftSolve.h>
#include <Spectra/SymEigsShiftSolver.h>
#include <Spectra/SymEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <limits>

#include "core/error.h"
#include "core/solver/internal/steps/full_space_step.h"
#include "core/solver/internal/steps/subspace_step.h"

namespace sd {
namespace {

StepConditioning from_extremes(double smallest, double largest) {
  StepConditioning c;
  c.smallest = smallest;
  c.largest = largest;
  c.condition = smallest > 0.0 ? largest / smallest : std::numeric_limits<double>::infinity();
  return c;
}

template <typename Solver>
double single_eigenvalue(Solver& solver, Spectra::SortRule rule, const char* which) {
  solver.init();
  solver.compute(rule, 1000, 1e-10);
  if (solver.info() != Spectra::CompInfo::Successful)
    throw Error(ErrorCode::NumericalFailure,
                std::string("step conditioning: Lanczos did not converge for the ") + which + " eigenvalue");
  return solver.eigenvalues()[0];
}

}  // namespace

StepConditioning full_space_conditioning(const DeformationEnergy& energy, const Vertices& X) {
  const FullSpaceStep full(energy);
  const Eigen::SparseMatrix<double> H = full.normal_matrix(energy.jacobian(X));
  const Eigen::Index n = H.rows();
  const int basis = static_cast<int>(std::min<Eigen::Index>(n, 30));
  Spectra::SparseSymMatProd<double> product(H);
  Spectra::SymEigsSolver<Spectra::SparseSymMatProd<double>> top(product, 1, basis);
  const double largest = single_eigenvalue(top, Spectra::SortRule::LargestAlge, "largest");
  // Shift-invert just below 0 (H may be singular: single-vertex handles leave a rotation free).
  const double sigma = -1e-14 * largest;
  Spectra::SparseSymShiftSolve<double> inverse(H);
  Spectra::SymEigsShiftSolver<Spectra::SparseSymShiftSolve<double>> bottom(inverse, 1, basis, sigma);
  const double smallest = single_eigenvalue(bottom, Spectra::SortRule::LargestMagn, "smallest");
  return from_extremes(smallest, largest);
}

StepConditioning subspace_conditioning(const DeformationEnergy& energy, const BasisMatrix& W, const Vertices& X,
                                       bool in_orthonormal_basis, double memory_budget_bytes) {
  const SubspaceStep sub(energy, W);
  const Eigen::MatrixXd JW = sub.dense_jacobian(energy.jacobian(X), memory_budget_bytes);
  const Eigen::Index m = W.cols();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(3 * m, 3 * m);
  A.selfadjointView<Eigen::Lower>().rankUpdate(JW.transpose());
  A = A.selfadjointView<Eigen::Lower>();
  Eigen::VectorXd values;
  if (in_orthonormal_basis) {
    const Eigen::MatrixXd Wd = W.to_dense();
    const Eigen::MatrixXd G = Wd.transpose() * Wd;
    Eigen::MatrixXd G3 = Eigen::MatrixXd::Zero(3 * m, 3 * m);
    for (int a = 0; a < 3; ++a) G3.block(a * m, a * m, m, m) = G;  // unknowns ordered axis * m + column
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, G3, Eigen::EigenvaluesOnly);
    if (eig.info() != Eigen::Success)
      throw Error(ErrorCode::NumericalFailure, "step conditioning: W^T W is not positive definite");
    values = eig.eigenvalues();
  } else {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
    values = eig.eigenvalues();
  }
  return from_extremes(values.minCoeff(), values.maxCoeff());
}

}  // namespace sd
