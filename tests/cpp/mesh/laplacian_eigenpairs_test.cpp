// The Laplace-Beltrami eigenpairs (-L phi = lambda M phi) from shift-invert Lanczos against Eigen's dense
// generalized eigensolver, their residuals and M-orthonormality, genus and components, and the refusals.
#include "core/mesh/laplacian_eigenpairs.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <string>

#include "core/error.h"
#include "core/mesh/cotan_laplacian.h"
#include "core/mesh/mass_matrix.h"
#include "core/mesh/shapes.h"
#include "test_support.h"

namespace sd {
namespace {

using test::expect_error;

// An icosphere with radial noise: no symmetry, so no repeated eigenvalues and the eigenvectors are unique up to
// sign. 642 vertices: above the dense limit, so Lanczos runs.
Mesh bumpy_sphere(unsigned seed) {
  Mesh m = make_icosphere(3, 1.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.9, 1.1);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) m.V.row(i) *= u(rng);
  return m;
}

// Largest relative residual |K phi - lambda M phi| / (lambda |M phi|) over the non-zero pairs (K = -L); for the
// zero ones (constants per component), |K phi| / (1e-4 |K| |phi|), so that 1e-8 means 1e-12 |K| |phi|.
double worst_residual(const Mesh& mesh, const Eigenpairs& pairs) {
  const Eigen::SparseMatrix<double> K = -cotan_laplacian(mesh.V, mesh.F);
  const double norm_K = Eigen::MatrixXd(K).cwiseAbs().rowwise().sum().maxCoeff();
  const double zero = 1e-9 * pairs.values.cwiseAbs().maxCoeff();
  double worst = 0;
  for (Eigen::Index j = 0; j < pairs.values.size(); ++j) {
    const Eigen::VectorXd phi = pairs.vectors.col(j);
    const Eigen::VectorXd Kphi = K * phi, Mphi = pairs.mass.cwiseProduct(phi);
    const double scale =
        std::abs(pairs.values[j]) > zero ? std::abs(pairs.values[j]) * Mphi.norm() : 1e-4 * norm_K * phi.norm();
    worst = std::max(worst, (Kphi - pairs.values[j] * Mphi).norm() / scale);
  }
  return worst;
}

double orthonormality_error(const Eigenpairs& pairs) {
  const Eigen::MatrixXd G = pairs.vectors.transpose() * pairs.mass.asDiagonal() * pairs.vectors;
  return (G - Eigen::MatrixXd::Identity(G.rows(), G.cols())).cwiseAbs().maxCoeff();
}

TEST(LaplacianEigenpairs, LanczosMatchesTheDenseGeneralizedEigensolver) {
  const Mesh mesh = bumpy_sphere(1);
  ASSERT_GT(mesh.V.rows(), kDenseEigenVertexLimit);
  EigenpairOptions options;
  options.count = 12;
  const Eigenpairs pairs = laplacian_eigenpairs(mesh.V, mesh.F, options);
  ASSERT_FALSE(pairs.dense);
  const Eigen::MatrixXd K = -Eigen::MatrixXd(cotan_laplacian(mesh.V, mesh.F));
  const Eigen::VectorXd mass = lumped_mass(mesh.V, mesh.F);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(K, Eigen::MatrixXd(mass.asDiagonal()));
  const double scale = dense.eigenvalues()[options.count - 1];
  for (int j = 0; j < options.count; ++j) {
    EXPECT_NEAR(pairs.values[j], dense.eigenvalues()[j], 1e-8 * scale) << "eigenvalue " << j;
    // The same vector up to sign: |phi_lanczos^T M phi_dense| = 1.
    const double overlap = pairs.vectors.col(j).dot(mass.cwiseProduct(dense.eigenvectors().col(j)));
    EXPECT_NEAR(std::abs(overlap), 1.0, 1e-8) << "eigenvector " << j;
  }
  EXPECT_NEAR(pairs.values[0], 0.0, 1e-10 * scale) << "the constant";
  EXPECT_LE(worst_residual(mesh, pairs), 1e-8);
  EXPECT_LE(orthonormality_error(pairs), 1e-10);
  EXPECT_GT(pairs.operations, 0);
  std::cout << "[          ] residual " << worst_residual(mesh, pairs) << ", M-orthonormality "
            << orthonormality_error(pairs) << ", " << pairs.operations << " solves\n";
}

TEST(LaplacianEigenpairs, GenusOneTorusHasOneZeroEigenvalueAndAccuratePairs) {
  const Mesh torus = make_torus(1.0, 0.35, 40, 16);
  EigenpairOptions options;
  options.count = 20;
  const Eigenpairs pairs = laplacian_eigenpairs(torus.V, torus.F, options);
  ASSERT_FALSE(pairs.dense);
  EXPECT_NEAR(pairs.values[0], 0.0, 1e-10 * pairs.values[1]);
  EXPECT_GT(pairs.values[1], 1e-3 * pairs.values[19]) << "only one zero eigenvalue: the torus is connected";
  for (int j = 1; j < 20; ++j) EXPECT_GE(pairs.values[j], pairs.values[j - 1]) << "ascending";
  EXPECT_LE(worst_residual(torus, pairs), 1e-8);
  EXPECT_LE(orthonormality_error(pairs), 1e-10);
  // The lowest mode of a thin torus runs around the big circle: lambda_1 ~ 1 / R^2 (R = major radius, here 1).
  EXPECT_NEAR(pairs.values[1], 1.0, 0.25);
}

TEST(LaplacianEigenpairs, SmallMeshesAreSolvedDenselyAndEachComponentAddsAZero) {
  // Two disjoint spheres (162 + 162 vertices > the dense limit? no: 324): shift one copy.
  Mesh a = make_icosphere(2, 1.0), two;
  two.V.resize(2 * a.V.rows(), 3);
  two.V << a.V, a.V.rowwise() + Eigen::RowVector3d(3, 0, 0);
  two.F.resize(2 * a.F.rows(), 3);
  two.F << a.F, a.F.array() + static_cast<int>(a.V.rows());
  EigenpairOptions options;
  options.count = 4;
  const Eigenpairs small = laplacian_eigenpairs(a.V, a.F, options);
  EXPECT_TRUE(small.dense);
  EXPECT_LE(worst_residual(a, small), 1e-8);
  EXPECT_LE(orthonormality_error(small), 1e-10);
  const Eigenpairs pairs = laplacian_eigenpairs(two.V, two.F, options);
  EXPECT_NEAR(pairs.values[0], 0.0, 1e-10 * pairs.values[2]);
  EXPECT_NEAR(pairs.values[1], 0.0, 1e-10 * pairs.values[2]) << "second component, second zero";
  EXPECT_GT(pairs.values[2], 1.0);  // a unit sphere's first non-zero eigenvalue is 2
  EXPECT_LE(worst_residual(two, pairs), 1e-8);
}

TEST(LaplacianEigenpairs, RefusesBadCountsTooMuchMemoryAndStopsWhenCancelled) {
  const Mesh mesh = bumpy_sphere(2);
  EigenpairOptions options;
  options.count = 0;
  expect_error([&] { laplacian_eigenpairs(mesh.V, mesh.F, options); }, "from 1 to 641");
  options.count = 642;
  expect_error([&] { laplacian_eigenpairs(mesh.V, mesh.F, options); }, "from 1 to 641");
  options.count = 50;
  options.memory_budget_bytes = 100000;
  expect_error([&] { laplacian_eigenpairs(mesh.V, mesh.F, options); }, "MB (eigenvectors and the Lanczos basis)",
               ErrorCode::MemoryBudget);
  options.memory_budget_bytes = std::size_t(1) << 30;
  std::vector<double> seen;
  options.progress = [&](double f) {
    seen.push_back(f);
    return f < 0.3;
  };
  expect_error([&] { laplacian_eigenpairs(mesh.V, mesh.F, options); }, "eigen-decomposition cancelled",
               ErrorCode::Cancelled);
  ASSERT_FALSE(seen.empty());
  EXPECT_GE(seen.back(), 0.3);
  seen.clear();
  options.progress = [&](double f) {
    seen.push_back(f);
    return true;
  };
  laplacian_eigenpairs(mesh.V, mesh.F, options);
  ASSERT_GE(seen.size(), 3u);
  EXPECT_EQ(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), 1.0);
  for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]) << "progress never goes back";
}

}  // namespace
}  // namespace sd
