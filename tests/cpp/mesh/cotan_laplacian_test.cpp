#include "core/mesh/cotan_laplacian.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/mesh/shapes.h"

namespace sd {
namespace {

std::vector<std::pair<std::string, Mesh>> fixture_meshes() {
  return {{"icosphere(2)", make_icosphere(2, 1.3)},
          {"box(2x3x4, 3)", make_box(2, 3, 4, 3)},
          {"capsule", make_capsule(2.0, 0.5, 4, 5, 12)},
          {"bar cage", make_bar_cage(-1.5, 1.5, 0.6, 0.4, 4)}};
}

TEST(CotanLaplacian, RowsSumToZeroAndMatrixIsSymmetric) {
  for (const auto& [name, mesh] : fixture_meshes()) {
    const Eigen::SparseMatrix<double> L = cotan_laplacian(mesh.V, mesh.F);
    ASSERT_EQ(L.rows(), mesh.V.rows()) << name;
    const double scale = L.diagonal().cwiseAbs().maxCoeff();
    const Eigen::VectorXd row_sums = L * Eigen::VectorXd::Ones(L.cols());
    EXPECT_LE(row_sums.cwiseAbs().maxCoeff(), 1e-12 * scale) << name;
    const Eigen::SparseMatrix<double> asym = L - Eigen::SparseMatrix<double>(L.transpose());
    EXPECT_LE(Eigen::MatrixXd(asym).cwiseAbs().maxCoeff(), 1e-14 * scale) << name;
  }
}

TEST(CotanLaplacian, IsNegativeSemidefiniteWithOneZeroEigenvaluePerComponent) {
  for (const auto& [name, mesh] : fixture_meshes()) {
    const Eigen::MatrixXd L = Eigen::MatrixXd(cotan_laplacian(mesh.V, mesh.F));
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(L);
    const Eigen::VectorXd lambda = eig.eigenvalues();  // ascending
    const double scale = lambda.cwiseAbs().maxCoeff();
    EXPECT_LE(lambda(lambda.size() - 1), 1e-12 * scale) << name;
    // Connected mesh: only the constant vector is in the kernel.
    EXPECT_LT(lambda(lambda.size() - 2), -1e-8 * scale) << name;
  }
}

// Corner tetrahedron: origin and the three unit points. Three right isosceles faces and one equilateral
// face, so every cotangent is 0, 1 or 1/sqrt(3).
TEST(CotanLaplacian, CornerTetrahedronHasKnownCotangents) {
  Vertices V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Faces F(4, 3);
  F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;  // outward
  const Eigen::MatrixXd L = Eigen::MatrixXd(cotan_laplacian(V, F));
  const double c60 = 1.0 / std::sqrt(3.0);
  // Edge 0-1: opposite angles are 45 degrees at vertex 2 and at vertex 3.
  EXPECT_NEAR(L(0, 1), (1.0 + 1.0) / 2, 1e-15);
  EXPECT_NEAR(L(0, 2), 1.0, 1e-15);
  EXPECT_NEAR(L(0, 3), 1.0, 1e-15);
  // Edge 1-2: right angle at the origin (cot 0) and 60 degrees at vertex 3.
  EXPECT_NEAR(L(1, 2), (0.0 + c60) / 2, 1e-15);
  EXPECT_NEAR(L(1, 3), c60 / 2, 1e-15);
  EXPECT_NEAR(L(2, 3), c60 / 2, 1e-15);
  EXPECT_NEAR(L(0, 0), -3.0, 1e-14);
  EXPECT_NEAR(L(1, 1), -(1.0 + c60), 1e-14);
}

TEST(CotanLaplacian, RegularTetrahedronHasEqualWeights) {
  Vertices V(4, 3);
  V << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  Faces F(4, 3);
  F << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
  const Eigen::MatrixXd L = Eigen::MatrixXd(cotan_laplacian(V, F));
  const double w = 1.0 / std::sqrt(3.0);  // (cot 60 + cot 60) / 2
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(L(i, j), i == j ? -3 * w : w, 1e-14) << i << "," << j;
}

// An obtuse angle gives a negative cotangent, which is kept (the header's convention).
TEST(CotanLaplacian, ObtuseAngleGivesNegativeWeight) {
  // Flat kite: triangles (0,1,2) and (0,3,1) share edge 0-1; the angle at 2 is 120 degrees.
  Vertices V(4, 3);
  V << -1, 0, 0, 1, 0, 0, 0, 1.0 / std::sqrt(3.0), 0, 0, -1, 0;
  Faces F(2, 3);
  F << 0, 1, 2, 0, 3, 1;
  const Eigen::MatrixXd L = Eigen::MatrixXd(cotan_laplacian(V, F));
  // cot 120 = -1/sqrt(3); the angle at vertex 3 is 90 degrees (cot 0).
  EXPECT_NEAR(L(0, 1), -1.0 / std::sqrt(3.0) / 2, 1e-15);
}

TEST(CotanLaplacian, DegenerateTriangleAndBadIndexThrow) {
  Vertices V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  Faces F(1, 3);
  F << 0, 1, 2;
  EXPECT_THROW(cotan_laplacian(V, F), Error);
  F << 0, 1, 3;
  EXPECT_THROW(cotan_laplacian(V, F), Error);
}

}  // namespace
}  // namespace sd
