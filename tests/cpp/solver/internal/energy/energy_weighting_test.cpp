// The weights of the energy's terms (energy_weighting.h): the uniform weighting is the report's energy
// unchanged, the area weighting integrates over the surface and weighs each handle group as a whole.
#include "core/solver/internal/energy/energy_weighting.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/mesh/cotan_laplacian.h"
#include "core/mesh/shapes.h"
#include "core/solver/internal/energy/deformation_energy.h"

namespace sd {
namespace {

TEST(EnergyWeighting, UniformIsTheReportsEnergy) {
  const Mesh capsule = make_capsule(2.0, 0.4, 4, 6, 12);
  DeformationEnergy energy(capsule.V, capsule.F, EnergyWeighting::Uniform);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(capsule.V, capsule.F);
  EXPECT_EQ(Eigen::MatrixXd(energy.laplacian() - L).cwiseAbs().maxCoeff(), 0.0);
  energy.set_handles({0, 5, 9}, {1, 2});
  energy.set_position_weight(3.0);
  EXPECT_TRUE(energy.handle_row_weights().isApproxToConstant(3.0, 0.0));
}

TEST(EnergyWeighting, AreaScalesRowsByTheReferenceOverTheVertexArea) {
  const Mesh capsule = make_capsule(2.0, 0.4, 4, 6, 12);
  const EnergyWeights weights(capsule.V, capsule.F);
  const Eigen::VectorXd& A = weights.vertex_areas();
  EXPECT_NEAR(weights.reference_area(), A.sum() / kReferenceVertexCount, 1e-15 * A.sum());
  const Eigen::VectorXd s = weights.laplacian_row_scales(EnergyWeighting::Area);
  for (Eigen::Index i = 0; i < A.size(); ++i) EXPECT_NEAR(s[i] * s[i] * A[i], weights.reference_area(), 1e-12 * A[i]);
  // Scaled rows still sum to zero (translations cost nothing).
  const DeformationEnergy energy(capsule.V, capsule.F, EnergyWeighting::Area);
  const Eigen::VectorXd row_sums = energy.laplacian() * Eigen::VectorXd::Ones(A.size());
  EXPECT_LE(row_sums.cwiseAbs().maxCoeff(), 1e-12 * Eigen::MatrixXd(energy.laplacian()).cwiseAbs().maxCoeff());
}

// A group pulls with the reference vertices it covers (at least one), spread by area; the uniform weighting
// gives every handle vertex 1.
TEST(EnergyWeighting, HandleGroupsPullWithTheirAreaAndAtLeastOneReferenceVertex) {
  const Mesh sphere = make_icosphere(5, 1.0);  // 10k vertices: each smaller than a reference vertex
  const EnergyWeights weights(sphere.V, sphere.F);
  const Eigen::VectorXd& A = weights.vertex_areas();
  std::vector<int> big;  // a cap of many vertices
  for (int i = 0; i < sphere.V.rows(); ++i)
    if (sphere.V(i, 2) > 0.8) big.push_back(i);
  std::vector<int> vertices = big;
  vertices.push_back(static_cast<int>(sphere.V.rows()) - 1);  // and one vertex alone (not in the cap)
  ASSERT_LT(sphere.V(vertices.back(), 2), 0.8);
  const std::vector<int> sizes{static_cast<int>(big.size()), 1};
  const Eigen::VectorXd c = weights.handle_coefficients(EnergyWeighting::Area, vertices, sizes);
  double cap_area = 0;
  for (int v : big) cap_area += A[v];
  ASSERT_GT(cap_area, weights.reference_area());
  EXPECT_NEAR(c.head(big.size()).sum(), cap_area / weights.reference_area(), 1e-12 * c.sum());
  for (size_t k = 0; k < big.size(); ++k) EXPECT_NEAR(c[k], A[big[k]] / weights.reference_area(), 1e-12 * c[k]);
  ASSERT_LT(A[vertices.back()], weights.reference_area());
  EXPECT_DOUBLE_EQ(c[big.size()], 1.0);  // a single vertex keeps the pull of one reference vertex
  EXPECT_TRUE(weights.handle_coefficients(EnergyWeighting::Uniform, vertices, sizes).isOnes());
  EXPECT_THROW(weights.handle_coefficients(EnergyWeighting::Area, vertices, {1}), Error);
}

// Switching the weighting rebuilds the Laplacian terms: the rest pose stays a zero of the residual.
TEST(EnergyWeighting, RestPoseHasZeroResidualInEitherWeighting) {
  const Mesh capsule = make_capsule(2.0, 0.4, 4, 6, 12);
  DeformationEnergy energy(capsule.V, capsule.F, EnergyWeighting::Area);
  energy.set_handles({0, 1, 2});
  for (EnergyWeighting w : {EnergyWeighting::Area, EnergyWeighting::Uniform, EnergyWeighting::Area}) {
    energy.set_weighting(w);
    const EnergyEvaluation e = energy.evaluate(capsule.V);
    EXPECT_LE(e.laplacian_residual.cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_EQ(e.position_energy, 0.0);
  }
}

}  // namespace
}  // namespace sd
