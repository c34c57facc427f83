#include "core/basis/harmonic_coordinates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/parallel/thread_pool.h"
#include "core/basis/mean_value_coordinates.h"
#include "test_support.h"
#include "basis/cage_fixtures.h"

namespace sd {
namespace {

Eigen::MatrixXd harmonic(const Vertices& points, const Mesh& cage, int resolution, HarmonicReport* details = nullptr,
                         MvcReport* report = nullptr) {
  HarmonicOptions options;
  options.resolution = resolution;
  return harmonic_coordinates(points, cage, {}, options, report, details).to_dense();
}

double max_row_sum_error(const Eigen::MatrixXd& W) { return (W.rowwise().sum().array() - 1.0).abs().maxCoeff(); }

double linear_precision(const Eigen::MatrixXd& W, const Mesh& cage, const Vertices& points) {
  return ((W * cage.V) - points).rowwise().norm().maxCoeff() / bounding_box_diagonal(cage.V);
}

// The goals on procedural cages, convex and concave: weights >= -1e-9, rows summing to 1 within 1e-6
// (here 1e-10: the solve is direct), linear precision within 2e-2 of the diagonal (here far better: exact at
// grid nodes, and to about the cell size in cells next to the cage).
TEST(HarmonicCoordinates, NonNegativePartitionOfUnityAndLinearPrecision) {
  const test::BentBar bent = test::bent_bar();
  const struct {
    const char* name;
    Mesh cage;
    Vertices points;
  } cases[] = {{"box", make_box(2, 1.4, 1, 2), test::random_points(200, {-0.95, -0.65, -0.45}, {0.95, 0.65, 0.45}, 3)},
               {"star", test::star_cage(), test::random_ball_points(200, 0.45, 4)},
               {"L prism", test::l_prism(), test::random_points(100, {0.05, 0.05, 0.05}, {0.95, 1.95, 0.95}, 5)},
               {"bent bar", bent.cage, bent.mesh.V}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    HarmonicReport details;
    MvcReport report;
    const Eigen::MatrixXd W = harmonic(c.points, c.cage, 20, &details, &report);
    EXPECT_GE(W.minCoeff(), -1e-9);
    EXPECT_EQ(report.min_weight, W.minCoeff());
    EXPECT_LE(max_row_sum_error(W), 1e-10);
    const double precision = linear_precision(W, c.cage, c.points);
    EXPECT_LE(precision, 2e-2);
    std::printf(
        "[ harmonic ] %s: resolution %d, %d unknowns, min weight %.2g, row-sum error %.1e, linear precision "
        "%.1e x diagonal, %d of %d points in cells next to the cage\n",
        c.name, details.resolution, details.unknowns, W.minCoeff(), max_row_sum_error(W), precision,
        details.boundary_cells, int(c.points.rows()));
  }
}

// Away from the cage (all 8 corners of a point's cell inside) linear precision is exact: the discrete Laplacian
// reproduces linear functions, and so does trilinear interpolation.
TEST(HarmonicCoordinates, LinearPrecisionIsExactAwayFromTheCage) {
  const Mesh cage = test::l_prism();
  const Vertices points = test::random_points(100, {0.3, 0.3, 0.3}, {0.7, 1.7, 0.7}, 8);
  HarmonicReport details;
  const Eigen::MatrixXd W = harmonic(points, cage, 24, &details);
  EXPECT_EQ(details.boundary_cells, 0);
  EXPECT_LE(linear_precision(W, cage, points), 1e-12);
}

// Grid convergence: the weights at fixed points approach the finest grid's as the resolution grows.
TEST(HarmonicCoordinates, ConvergeAsTheGridIsRefined) {
  const Mesh cage = test::star_cage();
  const Vertices points = test::random_ball_points(50, 0.4, 9);
  const Eigen::MatrixXd finest = harmonic(points, cage, 40);
  double previous = std::numeric_limits<double>::infinity();
  for (int resolution : {8, 12, 20}) {
    const double difference = (harmonic(points, cage, resolution) - finest).cwiseAbs().rowwise().sum().maxCoeff();
    std::printf("[ harmonic ] star, resolution %2d: largest row L1 difference from resolution 40: %.2e\n", resolution,
                difference);
    EXPECT_LT(difference, 0.75 * previous) << resolution;
    previous = difference;
  }
  EXPECT_LT(previous, 0.05);
}

// Unlike mean value coordinates, harmonic weights do not reach through the cage's concavity: in the bent bar
// the weight of the cage vertices at one end of the C, seen from the other end, stays tiny.
TEST(HarmonicCoordinates, StayNonNegativeWhereMeanValueCoordinatesGoNegative) {
  const test::BentBar bent = test::bent_bar();
  const Eigen::MatrixXd W = harmonic(bent.mesh.V, bent.cage, 20);
  const Eigen::MatrixXd M = mean_value_coordinates(bent.mesh.V, bent.cage).to_dense();
  EXPECT_LT(M.minCoeff(), -1e-3);
  EXPECT_GE(W.minCoeff(), -1e-9);
}

TEST(HarmonicCoordinates, ThreadCountsDoNotChangeTheResult) {
  const test::BentBar bent = test::bent_bar();
  const int saved = parallel::threads();
  parallel::set_threads(1);
  const Eigen::MatrixXd one = harmonic(bent.mesh.V, bent.cage, 20);
  for (int threads : {2, 3}) {
    parallel::set_threads(threads);
    EXPECT_EQ((harmonic(bent.mesh.V, bent.cage, 20) - one).cwiseAbs().maxCoeff(), 0.0) << threads << " threads";
  }
  parallel::set_threads(saved);
}

TEST(HarmonicCoordinates, ChoosesTheResolutionFromTheCage) {
  // About the same number of unknowns for a cage and its scaled copy, and more cells for a thinner cage.
  Mesh big = test::star_cage();
  big.V *= 40;
  EXPECT_EQ(harmonic_resolution(test::star_cage(), {}), harmonic_resolution(big, {}));
  EXPECT_GT(harmonic_resolution(make_box(4, 0.5, 0.5), {}), harmonic_resolution(make_box(1, 1, 1), {}));
  HarmonicOptions fixed;
  fixed.resolution = 17;
  EXPECT_EQ(harmonic_resolution(big, fixed), 17);
  HarmonicReport details;
  harmonic(test::random_ball_points(20, 0.4, 2), test::star_cage(), 0, &details);
  EXPECT_EQ(details.resolution, harmonic_resolution(test::star_cage(), {}));
  EXPECT_NEAR(details.unknowns, HarmonicOptions::kDefaultInteriorNodes, 0.3 * HarmonicOptions::kDefaultInteriorNodes);
}

TEST(HarmonicCoordinates, RefusesBadInputBeforeAllocating) {
  const Mesh cage = test::l_prism();
  const Vertices points = test::random_points(10, {0.1, 0.1, 0.1}, {0.9, 0.9, 0.9}, 1);
  HarmonicOptions options;
  options.resolution = 4;
  test::expect_error([&] { harmonic_coordinates(points, cage, {}, options); }, "resolution must be",
                     ErrorCode::InvalidArgument);
  // The grid alone over the budget: refused before it is built.
  options.resolution = 1000;
  MvcOptions budget;
  budget.memory_budget_bytes = 100'000'000;
  test::expect_error([&] { harmonic_coordinates(points, cage, budget, options); }, "the grid (",
                     ErrorCode::MemoryBudget);
  // The factor over the budget: refused before it is allocated.
  options.resolution = 40;
  budget.memory_budget_bytes = 3'000'000;
  test::expect_error([&] { harmonic_coordinates(points, cage, budget, options); }, "the factor of the grid Laplacian",
                     ErrorCode::MemoryBudget);
  Vertices outside = points;
  outside.row(4) << 1.5, 1.5, 0.5;  // in the notch of the L
  test::expect_error([&] { harmonic_coordinates(outside, cage, {}); }, "1 of 10 mesh vertices are outside",
                     ErrorCode::MeshOutsideCage);
}

TEST(HarmonicCoordinates, ReportsProgressAndCanBeCancelled) {
  const test::BentBar bent = test::bent_bar();
  HarmonicOptions options;
  options.resolution = 20;
  test::expect_progress_and_cancel(
      [&](const MvcOptions& binding) { harmonic_coordinates(bent.mesh.V, bent.cage, binding, options); });
}

// The goals on real cages.
class HarmonicRealPairs : public ::testing::TestWithParam<test::SharedPair> {};

TEST_P(HarmonicRealPairs, Goals) {
  const test::SharedPair pair = GetParam();
  SD_REQUIRE_SHARED_DATA(pair.mesh);
  SD_REQUIRE_SHARED_DATA(pair.cage);
  const Mesh mesh = test::load_shared_mesh(pair.mesh);
  const Mesh cage = test::load_shared_mesh(pair.cage);
  HarmonicReport details;
  const Eigen::MatrixXd W = harmonic(mesh.V, cage, 0, &details);
  const double precision = ((W * cage.V) - mesh.V).rowwise().norm().maxCoeff() / bounding_box_diagonal(mesh.V);
  EXPECT_GE(W.minCoeff(), -1e-9);
  EXPECT_LE(max_row_sum_error(W), 1e-6);
  EXPECT_LE(precision, 2e-2);
  std::printf(
      "[ pair     ] %s + %s: resolution %d, %d unknowns, min weight %.2g, row-sum error %.1e, linear "
      "precision %.1e x diagonal, factor %.2f s, solve %.2f s\n",
      pair.mesh, pair.cage, details.resolution, details.unknowns, W.minCoeff(), max_row_sum_error(W), precision,
      details.factor_seconds, details.solve_seconds);
}

INSTANTIATE_TEST_SUITE_P(SharedData, HarmonicRealPairs,
                         ::testing::Values(test::SharedPair{"armadillo.obj", "armadillo_cage.obj"},
                                           test::SharedPair{"gargoyle.obj", "gargoyle_cage.obj"}),
                         test::shared_pair_name);

}  // namespace
}  // namespace sd
