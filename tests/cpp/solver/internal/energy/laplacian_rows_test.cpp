// The factored Laplacian rows M = L (x) I3 - J_delta_hat (laplacian_rows.h) against the explicit sparse
// matrix built from the Laplacian and the Jacobian of delta_hat (itself checked against finite differences in
// laplacian_coordinates_test), at a deformed pose and with several vectors at once.
#include "core/solver/internal/energy/laplacian_rows.h"

#include <gtest/gtest.h>

#include <random>

#include "core/mesh/cotan_laplacian.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/energy/laplacian_coordinates.h"
#include "core/mesh/shapes.h"

namespace sd {
namespace {

Eigen::SparseMatrix<double> interleaved_laplacian(const Eigen::SparseMatrix<double>& L) {
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < L.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it)
      for (int a = 0; a < 3; ++a) t.emplace_back(3 * it.row() + a, 3 * it.col() + a, it.value());
  Eigen::SparseMatrix<double> out(3 * L.rows(), 3 * L.cols());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

TEST(LaplacianRows, ProductsMatchTheExplicitMatrix) {
  const Mesh capsule = make_capsule(2.0, 0.4, 4, 6, 12);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vertices X = capsule.V;
  for (Eigen::Index i = 0; i < X.rows(); ++i) X.row(i) += 0.03 * Eigen::RowVector3d(u(rng), u(rng), u(rng));
  X.col(1) += 0.2 * X.col(0).array().square().matrix();  // a bend, so rings are not at rest

  const DeformationEnergy energy(capsule.V, capsule.F);
  const EnergyJacobian J = energy.jacobian(X);
  const LaplacianCoordinates lc(capsule.V, capsule.F, energy.laplacian());  // the weighted rows S L
  const Eigen::SparseMatrix<double> M = interleaved_laplacian(energy.laplacian()) - lc.jacobian(X);
  const Eigen::SparseMatrix<double> from_factors = J.laplacian_rows_matrix();
  EXPECT_LE(Eigen::MatrixXd(M - from_factors).cwiseAbs().maxCoeff(), 1e-12 * Eigen::MatrixXd(M).cwiseAbs().maxCoeff());

  Eigen::MatrixXd Y(X.rows(), 6);
  for (Eigen::Index i = 0; i < Y.size(); ++i) Y.data()[i] = u(rng);
  const Eigen::MatrixXd MY = interleave(J.laplacian_rows(Y));
  const Eigen::MatrixXd expected = M * interleave(Y);
  EXPECT_LE((MY - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
  // M^T through J_f^T J_f: normal_product = M^T M y + w^2 Phi^T Phi y, no handles here.
  const Eigen::MatrixXd MtMY = interleave(J.normal_product(Y));
  const Eigen::MatrixXd expected_normal = Eigen::SparseMatrix<double>(M.transpose()) * expected;
  EXPECT_LE((MtMY - expected_normal).cwiseAbs().maxCoeff(), 1e-12 * expected_normal.cwiseAbs().maxCoeff());
}

// The transposed product reads a copy of the blocks in column order (laplacian_rows.h): linearising the same rows
// at another pose must renew it, or M^T would stay the first pose's.
TEST(LaplacianRows, ALinearisationAtAnotherPoseRenewsTheTransposedProduct) {
  const Mesh capsule = make_capsule(2.0, 0.4, 4, 6, 12);
  const DeformationEnergy energy(capsule.V, capsule.F);
  const LaplacianCoordinates lc(capsule.V, capsule.F, energy.laplacian());
  EnergyJacobian J = energy.jacobian(capsule.V);
  Vertices X = capsule.V;
  X.col(1) += 0.3 * X.col(0).array().square().matrix();
  energy.update_jacobian(X, J);
  const Eigen::SparseMatrix<double> M = interleaved_laplacian(energy.laplacian()) - lc.jacobian(X);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd Z(X.rows(), 3);
  for (Eigen::Index i = 0; i < Z.size(); ++i) Z.data()[i] = u(rng);
  const Eigen::MatrixXd MtZ = interleave(J.laplacian_rows_transpose(Z));
  const Eigen::MatrixXd expected = Eigen::SparseMatrix<double>(M.transpose()) * interleave(Z);
  EXPECT_LE((MtZ - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace sd
