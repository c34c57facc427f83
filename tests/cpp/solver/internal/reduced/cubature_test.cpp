// The reduced integration's samples and weights (cubature.h) and its training poses (training_poses.h).
#include "core/solver/internal/reduced/cubature.h"

#include <gtest/gtest.h>

#include "core/mesh/examples.h"
#include "core/mesh/shapes.h"
#include "core/mesh/volume.h"
#include "core/solver/internal/reduced/training_poses.h"
#include "core/basis/mean_value_coordinates.h"

namespace sd {
namespace {

struct Bound {
  Example model;
  DeformationEnergy energy;
  BasisMatrix W;
  explicit Bound(const std::string& name)
      : model(make_example(name)),
        energy(model.mesh.V, model.mesh.F),
        W(mean_value_coordinates(model.mesh.V, model.cage)) {}
};

TEST(Cubature, EveryVertexWithWeightOneOnSmallMeshes) {
  const Mesh capsule = make_capsule(2.0, 0.4, 4, 6, 12);
  const DeformationEnergy energy(capsule.V, capsule.F);
  const BasisMatrix W = mean_value_coordinates(capsule.V, make_bar_cage(-1.6, 1.6, 0.6, 0.6, 4));
  CubatureOptions o;
  o.max_samples = static_cast<int>(capsule.V.rows());
  const Cubature c = fit_cubature(energy, W, make_bar_cage(-1.6, 1.6, 0.6, 0.6, 4).V, o);
  ASSERT_EQ(c.samples.size(), static_cast<size_t>(capsule.V.rows()));
  EXPECT_TRUE(c.weights.isOnes());
  EXPECT_EQ(c.training_error, 0.0);
}

// Without a fit the weights are a quadrature rule: each sample's cell area over its own area, so the weighted
// sample areas add up to the surface's area (constants integrate exactly).
TEST(Cubature, SpreadSamplesIntegrateTheAreaExactly) {
  const Bound bar("bar");
  CubatureOptions o;
  o.training_poses = 0;
  o.test_poses = 0;
  const Cubature c = fit_cubature(bar.energy, bar.W, bar.model.cage.V, o);
  ASSERT_EQ(c.samples.size(), static_cast<size_t>(o.max_samples));
  const Eigen::VectorXd& area = bar.energy.weights().vertex_areas();
  double integral = 0.0;
  for (size_t k = 0; k < c.samples.size(); ++k)
    integral += c.weights[static_cast<Eigen::Index>(k)] * area[c.samples[k]];
  EXPECT_NEAR(integral, area.sum(), 1e-12 * area.sum());
  EXPECT_TRUE(std::is_sorted(c.samples.begin(), c.samples.end()));
  // Spread: no two samples closer than a fraction of the spacing an even spread would give.
  double closest = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < c.samples.size(); ++a)
    for (size_t b = a + 1; b < c.samples.size(); ++b)
      closest = std::min(closest, (bar.model.mesh.V.row(c.samples[a]) - bar.model.mesh.V.row(c.samples[b])).norm());
  const double spacing = std::sqrt(area.sum() / o.max_samples);
  EXPECT_GT(closest, 0.3 * spacing);
}

// The default rule (spread samples, quadrature weights) integrates held-out poses' energies and slopes to a few
// percent; the optional fit on training poses keeps the weights positive and matches its poses closely.
TEST(Cubature, QuadratureGeneralisesAndTheOptionalFitMatchesItsPoses) {
  const Bound sphere("sphere");
  const Cubature rule = fit_cubature(sphere.energy, sphere.W, sphere.model.cage.V);
  EXPECT_EQ(rule.samples.size(), 800u);
  EXPECT_EQ(rule.weights, rule.quadrature);
  EXPECT_GT(rule.test_error, 0.0);
  EXPECT_LT(rule.test_error, 0.15);
  CubatureOptions with_fit;
  with_fit.training_poses = 16;
  const Cubature fitted = fit_cubature(sphere.energy, sphere.W, sphere.model.cage.V, with_fit);
  EXPECT_GT(fitted.samples.size(), 700u);
  EXPECT_TRUE((fitted.weights.array() > 0.0).all());
  EXPECT_LT(fitted.training_error, 0.05);
  EXPECT_LT(fitted.test_error, 0.2);
}

TEST(Cubature, SameInputsGiveTheSameSamplesAndWeights) {
  const Bound bar("bar");
  const Cubature a = fit_cubature(bar.energy, bar.W, bar.model.cage.V),
                 b = fit_cubature(bar.energy, bar.W, bar.model.cage.V);
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.weights, b.weights);
}

// Training poses are smooth deformations of the rest mesh of moderate size: they move it (not the rest pose)
// by less than its diagonal, and they are the same for the same seed.
TEST(TrainingPoses, AreDeterministicDeformationsOfModerateSize) {
  const Bound bar("bar");
  const std::vector<Eigen::MatrixXd> poses = training_poses(bar.model.mesh.V, bar.W, bar.model.cage.V, 10, 7);
  ASSERT_EQ(poses.size(), 10u);
  const double diagonal = bounding_box_diagonal(bar.model.mesh.V);
  for (const Eigen::MatrixXd& P : poses) {
    Eigen::MatrixXd X;
    bar.W.multiply(P, X);
    const double moved = (X - bar.model.mesh.V).rowwise().norm().maxCoeff();
    EXPECT_GT(moved, 1e-3 * diagonal);
    EXPECT_LT(moved, diagonal);
  }
  EXPECT_EQ(poses[3], training_poses(bar.model.mesh.V, bar.W, bar.model.cage.V, 10, 7)[3]);
  EXPECT_NE(poses[3], training_poses(bar.model.mesh.V, bar.W, bar.model.cage.V, 10, 8)[3]);
}

}  // namespace
}  // namespace sd
