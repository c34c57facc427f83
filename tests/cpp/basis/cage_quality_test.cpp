#include "core/basis/cage_quality.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/mesh/shapes.h"
#include "core/mesh/volume.h"
#include "core/parallel/thread_pool.h"
#include "core/basis/mean_value_coordinates.h"
#include "test_support.h"

namespace sd {
namespace {

Mesh scaled(Mesh mesh, double s) {
  mesh.V *= s;
  return mesh;
}

Mesh shifted(Mesh mesh, double dx) {
  mesh.V.col(0).array() += dx;
  return mesh;
}

// The reference: smallest / largest eigenvalue of (1/rows) sum over every stride-th row of w_i w_i^T,
// computed densely from the whole matrix.
double reference_ratio(const BasisMatrix& W, int stride) {
  const Eigen::MatrixXd dense = W.to_dense();
  Eigen::MatrixXd sampled(0, dense.cols());
  for (int i = 0; i < dense.rows(); i += stride) {
    sampled.conservativeResize(sampled.rows() + 1, Eigen::NoChange);
    sampled.row(sampled.rows() - 1) = dense.row(i);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(sampled.transpose() * sampled);
  return std::max(0.0, eigen.eigenvalues()[0]) / eigen.eigenvalues().maxCoeff();
}

bool mentions(const CageQuality& q, const std::string& word) {
  for (const std::string& w : q.warnings)
    if (w.find(word) != std::string::npos) return true;
  return false;
}

// A sphere in a snug icosphere cage: every cage vertex has weight, every cage motion moves the mesh, the
// cage is a little larger than the mesh. Nothing to warn about.
TEST(CageQuality, SnugCageHasNoWarnings) {
  const Mesh mesh = make_icosphere(3, 1.0), cage = make_icosphere(1, 1.3);
  const BasisMatrix W = mean_value_coordinates(mesh.V, cage);
  const CageQuality q = cage_quality(W, mesh, cage);
  EXPECT_EQ(q.cage_vertices, 42);
  EXPECT_EQ(q.weak_vertices, 0);
  EXPECT_GT(q.min_column_max, 1e-2);
  EXPECT_GT(q.influence_ratio, 1e-4);
  EXPECT_EQ(q.weak_motions, 0);
  // Volumes of the two polyhedra: the ratio is the cube of the radii up to the inscribed-polyhedron factor.
  EXPECT_NEAR(q.volume_ratio, signed_volume(cage.V, cage.F) / signed_volume(mesh.V, mesh.F), 1e-12);
  EXPECT_GT(q.volume_ratio, 1.3 * 1.3 * 1.3 * 0.8);
  EXPECT_EQ(q.sampled_rows, mesh.V.rows());
  EXPECT_FALSE(q.poor()) << q.warnings.front();
}

// The same sphere in a long bar cage that reaches far beyond it: the far end's cage vertices have
// almost no weight and their motions barely move the mesh; the cage is many times the mesh's volume.
TEST(CageQuality, CageReachingFarFromTheMeshIsPoor) {
  const Mesh mesh = scaled(make_icosphere(3, 1.0), 0.4);
  const Mesh cage = make_bar_cage(-0.5, 30.0, 0.5, 0.5, 30);
  const BasisMatrix W = mean_value_coordinates(mesh.V, cage);
  const CageQuality q = cage_quality(W, mesh, cage);
  EXPECT_GT(q.weak_vertices, q.cage_vertices / 2) << "most of the bar is far from the sphere";
  EXPECT_LT(q.min_column_max, 1e-3);
  EXPECT_LT(q.influence_ratio, 1e-6);
  EXPECT_GT(q.weak_motions, 0);
  EXPECT_GT(q.volume_ratio, 20);
  EXPECT_TRUE(mentions(q, "no weight above")) << "weak vertices";
  EXPECT_TRUE(mentions(q, "motions of the cage barely move")) << "influence";
  EXPECT_TRUE(mentions(q, "times the mesh's volume")) << "volume";
}

// A loose cage (radius 3 around the unit sphere): every cage vertex has weight, but the cage is many times
// the mesh's volume. Looser cages also give smoother, more alike weights: the influence ratio falls with
// the radius (r 1.1: 0.17, 1.6: 2.5e-3, 3: 1.4e-6).
TEST(CageQuality, LooseCageWarnsAboutVolume) {
  const Mesh mesh = make_icosphere(3, 1.0);
  double previous = 1;
  for (double radius : {1.1, 1.6, 3.0}) {
    const Mesh cage = make_icosphere(1, radius);
    const CageQuality q = cage_quality(mean_value_coordinates(mesh.V, cage), mesh, cage);
    EXPECT_EQ(q.weak_vertices, 0);
    EXPECT_LT(q.influence_ratio, previous) << "radius " << radius;
    previous = q.influence_ratio;
    EXPECT_EQ(mentions(q, "times the mesh's volume"), radius == 3.0) << "radius " << radius;
  }
}

// The influence ratio is the eigenvalue ratio of W^T W over the sampled rows, also when only every k-th
// row is used, and the answer does not depend on the thread count.
TEST(CageQuality, InfluenceRatioMatchesDenseEigenvalues) {
  const Mesh mesh = shifted(scaled(make_icosphere(3, 1.0), 0.4), 1.0);
  const Mesh cage = make_bar_cage(-0.5, 4.0, 0.6, 0.6, 6);
  const BasisMatrix W = mean_value_coordinates(mesh.V, cage);
  const int n = static_cast<int>(mesh.V.rows());
  CageQualityOptions all, some;
  some.sample_rows = 100;
  some.rows_per_vertex = 1;
  const int stride = (n + 99) / 100;
  const CageQuality full = cage_quality(W, mesh, cage, all), sampled = cage_quality(W, mesh, cage, some);
  EXPECT_EQ(full.sampled_rows, n);
  EXPECT_EQ(sampled.sampled_rows, (n + stride - 1) / stride);
  EXPECT_NEAR(full.influence_ratio, reference_ratio(W, 1), 1e-9 * reference_ratio(W, 1) + 1e-15);
  EXPECT_NEAR(sampled.influence_ratio, reference_ratio(W, stride), 1e-9 * reference_ratio(W, stride) + 1e-15);
  const int before = parallel::threads();
  for (int threads : {1, 2, 4}) {
    parallel::set_threads(threads);
    EXPECT_EQ(cage_quality(W, mesh, cage, all).influence_ratio, full.influence_ratio) << threads << " threads";
  }
  parallel::set_threads(before);
}

TEST(CageQuality, LargeCagesSkipTheSpectrum) {
  const Mesh mesh = make_icosphere(2, 1.0), cage = make_icosphere(1, 1.3);
  CageQualityOptions options;
  options.max_spectrum_vertices = 41;
  const CageQuality q = cage_quality(mean_value_coordinates(mesh.V, cage), mesh, cage, options);
  EXPECT_TRUE(std::isnan(q.influence_ratio));
  EXPECT_EQ(q.sampled_rows, 0);
  EXPECT_FALSE(q.poor()) << "not computed is not a warning";
}

TEST(CageQuality, MismatchedSizesAreRefused) {
  const Mesh mesh = make_icosphere(2, 1.0), cage = make_icosphere(1, 1.3);
  const BasisMatrix W = mean_value_coordinates(mesh.V, cage);
  EXPECT_THROW(cage_quality(W, make_icosphere(1, 1.0), cage), Error);
  EXPECT_THROW(cage_quality(W, mesh, make_box(3, 3, 3)), Error);
}

// The shared cages: the cow's (docs/cage.md lists every shared pair's numbers) is flagged by its influence
// ratio although each of its vertices has some weight; the armadillo's and the boy's are not.
TEST(CageQuality, SharedCowCageIsPoorAndArmadilloCageIsNot) {
  SD_REQUIRE_SHARED_DATA("cow.obj");
  SD_REQUIRE_SHARED_DATA("armadillo.obj");
  const Mesh cow = test::load_shared_mesh("cow.obj"), cow_cage = test::load_shared_mesh("cow_cage.obj");
  const CageQuality q = cage_quality(mean_value_coordinates(cow.V, cow_cage), cow, cow_cage);
  EXPECT_LT(q.influence_ratio, 1e-6);
  EXPECT_TRUE(q.poor());
  const Mesh armadillo = test::load_shared_mesh("armadillo.obj"), cage = test::load_shared_mesh("armadillo_cage.obj");
  const CageQuality a = cage_quality(mean_value_coordinates(armadillo.V, cage), armadillo, cage);
  EXPECT_GT(a.influence_ratio, 1e-4);
  EXPECT_FALSE(a.poor()) << a.warnings.front();
}

}  // namespace
}  // namespace sd
