// The spectral basis B = [1, x0, y0, z0, phi_1 .. phi_k]: orthonormal in the area-weighted mass inner product,
// spanning the rest pose and the eigenvectors, on genus 0 and 1, and its refusals.
#include "core/basis/spectral_basis.h"

#include <gtest/gtest.h>

#include <climits>
#include <random>
#include <string>

#include "core/error.h"
#include "core/mesh/laplacian_eigenpairs.h"
#include "core/mesh/mass_matrix.h"
#include "core/mesh/shapes.h"
#include "test_support.h"

namespace sd {
namespace {

using test::expect_error;

Mesh bumpy_capsule() {
  Mesh m = make_capsule(2.0, 0.5, 6, 10, 16);  // 290 vertices: Lanczos, not the dense fallback
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (Eigen::Index i = 0; i < m.V.size(); ++i) m.V.data()[i] += u(rng);
  m.V.rowwise() += Eigen::RowVector3d(40, -7, 3);  // away from the origin: the basis must not care
  return m;
}

Eigen::VectorXd unit_mass(const Mesh& m) {
  const Eigen::VectorXd mass = lumped_mass(m.V, m.F);
  return mass / mass.sum();
}

TEST(SpectralBasis, ColumnsAreMassOrthonormalAndSpanTheRestPoseAndTheModes) {
  const Mesh mesh = bumpy_capsule();
  ASSERT_GT(mesh.V.rows(), kDenseEigenVertexLimit);
  SpectralOptions options;
  options.modes = 16;
  const SpectralBasis basis = spectral_basis(mesh, options);
  ASSERT_EQ(basis.B.cols(), 16 + 4);
  EXPECT_EQ(basis.dropped, 0);
  const Eigen::MatrixXd B = basis.B.to_dense();
  const Eigen::VectorXd w = unit_mass(mesh);
  const Eigen::MatrixXd G = B.transpose() * w.asDiagonal() * B;
  EXPECT_LE((G - Eigen::MatrixXd::Identity(20, 20)).cwiseAbs().maxCoeff(), 1e-8) << "B^T (M / area) B = I";
  EXPECT_LE((B.col(0).array() - 1.0).abs().maxCoeff(), 1e-12) << "the constant column stays 1";
  // The rest pose is in the span exactly: B C0 = X0.
  const double bbox = bounding_box_diagonal(mesh.V);
  EXPECT_LE((B * basis.rest_coefficients - Eigen::MatrixXd(mesh.V)).cwiseAbs().maxCoeff(),
            1e-12 * (bbox + mesh.V.cwiseAbs().maxCoeff()));
  // So is every eigenvector used: its projection onto span(B) is itself.
  EigenpairOptions eigen;
  eigen.count = 17;
  const Eigenpairs pairs = laplacian_eigenpairs(mesh.V, mesh.F, eigen);
  for (int j = 1; j < 17; ++j) {
    const Eigen::VectorXd phi = pairs.vectors.col(j);
    const Eigen::VectorXd projected = B * (B.transpose() * w.cwiseProduct(phi));
    EXPECT_LE((projected - phi).norm(), 1e-8 * phi.norm()) << "mode " << j;
  }
  ASSERT_EQ(basis.eigenvalues.size(), 17);
  EXPECT_NEAR(basis.eigenvalues[0], 0.0, 1e-10 * basis.eigenvalues[16]);
  EXPECT_GT(basis.operations, 0);
}

TEST(SpectralBasis, WorksOnAGenusOneTorusAndInSinglePrecision) {
  const Mesh torus = make_torus(1.0, 0.35, 40, 16);
  SpectralOptions options;
  options.modes = 10;
  options.single_precision = true;
  const SpectralBasis basis = spectral_basis(torus, options);
  ASSERT_EQ(basis.B.cols(), 14);
  EXPECT_TRUE(basis.B.single_precision());
  const Eigen::MatrixXd B = basis.B.to_dense();
  const Eigen::VectorXd w = unit_mass(torus);
  const Eigen::MatrixXd G = B.transpose() * w.asDiagonal() * B;
  EXPECT_LE((G - Eigen::MatrixXd::Identity(14, 14)).cwiseAbs().maxCoeff(), 1e-6) << "float32 storage";
  EXPECT_LE((B * basis.rest_coefficients - Eigen::MatrixXd(torus.V)).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(SpectralBasis, RefusesTooManyModesTooMuchMemoryAndStopsWhenCancelled) {
  const Mesh small = make_icosphere(1, 1.0);  // 42 vertices
  SpectralOptions options;
  options.modes = 38;
  expect_error([&] { spectral_basis(small, options); }, "must be from 1 to 37", ErrorCode::InvalidArgument);
  options.modes = 0;
  expect_error([&] { spectral_basis(small, options); }, "must be from 1 to 37");
  options.modes = INT_MAX;  // modes + 5 used to wrap around to a negative count
  expect_error([&] { spectral_basis(small, options); },
               "must be from 1 to 37 for this mesh of 42 vertices (B has modes + 4 columns); got 2147483647");
  // A tetrahedron has no room for any mode: the message names the smallest mesh, not "from 1 to 0".
  const Mesh tetrahedron{(Vertices(4, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1).finished(),
                         (Faces(4, 3) << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3).finished()};
  options.modes = 1;
  expect_error([&] { spectral_basis(tetrahedron, options); }, "needs a mesh of at least 6 vertices");
  const Mesh mesh = bumpy_capsule();
  options.modes = 40;
  options.memory_budget_bytes = 100000;
  expect_error([&] { spectral_basis(mesh, options); }, "MB (eigenvectors, the Lanczos basis and B",
               ErrorCode::MemoryBudget);
  options.memory_budget_bytes = std::size_t(1) << 30;
  options.progress = [](double f) { return f < 0.5; };
  expect_error([&] { spectral_basis(mesh, options); }, "cancelled", ErrorCode::Cancelled);
  double last = -1;
  options.progress = [&](double f) {
    EXPECT_GE(f, last);
    last = f;
    return true;
  };
  spectral_basis(mesh, options);
  EXPECT_EQ(last, 1.0);
}

}  // namespace
}  // namespace sd
