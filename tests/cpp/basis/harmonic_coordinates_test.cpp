#include "core/basis/harmonic_coordinates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/mesh/examples.h"
#include "core/timer.h"
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
  // The grid and a lower bound of its factor over the budget: refused before the grid is built (a factor over
  // the budget once counted: RefusesAFactorOverTheBudgetNamingAResolutionThatFits).
  options.resolution = 40;
  budget.memory_budget_bytes = 3'000'000;
  test::expect_error([&] { harmonic_coordinates(points, cage, budget, options); }, "the grid (",
                     ErrorCode::MemoryBudget);
  Vertices outside = points;
  outside.row(4) << 1.5, 1.5, 0.5;  // in the notch of the L
  test::expect_error([&] { harmonic_coordinates(outside, cage, {}); }, "1 of 10 mesh vertices are outside",
                     ErrorCode::MeshOutsideCage);
}

// The resolution an error message advises ("use resolution N or lower"), or 0.
int advised_resolution(const std::string& message) {
  const size_t at = message.find("use resolution ");
  return at == std::string::npos ? 0 : std::atoi(message.c_str() + at + 15);
}

std::string error_message(const std::function<void()>& call, ErrorCode code) {
  try {
    call();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

// Issue 32 item 3: on the bar, resolution 1024 failed with "allocator<T>::allocate exceeds maximum supported
// size" after 6 s and 2.9 GB, and 512 or 384 ran for minutes. Within the default budget (1 GB) each is
// refused before the grid is built, in well under a second, naming a resolution to try.
TEST(HarmonicCoordinates, RefusesAGridOverTheBudgetBeforeBuildingIt) {
  const Example bar = make_example("bar");
  for (int resolution : {1024, 512, 384, 256}) {
    SCOPED_TRACE(resolution);
    HarmonicOptions options;
    options.resolution = resolution;
    const Timer timer;
    const std::string message = error_message([&] { harmonic_coordinates(bar.mesh.V, bar.cage, {}, options); },
                                              resolution == 256 ? ErrorCode::InvalidArgument : ErrorCode::MemoryBudget);
    EXPECT_LT(timer.ms(), 500.0) << message;
    EXPECT_NE(message.find("the grid ("), std::string::npos) << message;
    const int advised = advised_resolution(message);
    EXPECT_GE(advised, HarmonicOptions::kMinResolution) << message;
    EXPECT_LT(advised, resolution) << message;
  }
}

// A resolution whose counted work is over the limit is refused before the factorization, naming a resolution
// whose work is under it; the caller may lift the limit (max_work 0) and get W.
TEST(HarmonicCoordinates, RefusesWorkOverTheLimitNamingAResolutionThatFits) {
  const Example bar = make_example("bar");
  HarmonicOptions options;
  options.resolution = 48;
  HarmonicReport details;
  harmonic_coordinates(bar.mesh.V, bar.cage, {}, options, nullptr, &details);
  EXPECT_GT(details.work, 0.0);
  options.max_work = details.work / 4;
  const Timer timer;
  const std::string message =
      error_message([&] { harmonic_coordinates(bar.mesh.V, bar.cage, {}, options); }, ErrorCode::InvalidArgument);
  EXPECT_LT(timer.ms(), 0.5 * 1e3 * details.factor_seconds + 200) << message;  // refused before factoring
  EXPECT_NE(message.find("multiply-adds at resolution 48"), std::string::npos) << message;
  const int advised = advised_resolution(message);
  ASSERT_GE(advised, HarmonicOptions::kMinResolution) << message;
  EXPECT_LT(advised, 48);
  options.resolution = advised;
  HarmonicReport fits;
  EXPECT_NO_THROW(harmonic_coordinates(bar.mesh.V, bar.cage, {}, options, nullptr, &fits)) << message;
  EXPECT_LE(fits.work, options.max_work);
  // Asked for explicitly, the long binding runs.
  options.resolution = 48;
  options.max_work = 0;
  EXPECT_NO_THROW(harmonic_coordinates(bar.mesh.V, bar.cage, {}, options));
}

// The same for memory: a factor over a small budget is refused (counted after the ordering, before the factor
// is allocated), naming a resolution that fits the budget.
TEST(HarmonicCoordinates, RefusesAFactorOverTheBudgetNamingAResolutionThatFits) {
  const Example bar = make_example("bar");
  HarmonicOptions options;
  options.resolution = 48;
  MvcOptions budget;
  budget.memory_budget_bytes = 8'000'000;
  const std::string message =
      error_message([&] { harmonic_coordinates(bar.mesh.V, bar.cage, budget, options); }, ErrorCode::MemoryBudget);
  const int advised = advised_resolution(message);
  ASSERT_GE(advised, HarmonicOptions::kMinResolution) << message;
  options.resolution = advised;
  EXPECT_NO_THROW(harmonic_coordinates(bar.mesh.V, bar.cage, budget, options)) << message;
}

// Progress is reported during the factorization (every few tens of milliseconds, row by row), so cancelling
// takes effect there, not after it (the 512: minutes without a report).
TEST(HarmonicCoordinates, CancelsDuringTheFactorization) {
  const Example bar = make_example("bar");
  HarmonicOptions options;
  options.resolution = 56;
  std::vector<double> seen;
  MvcOptions binding;
  binding.progress = [&](double fraction) {
    seen.push_back(fraction);
    return true;
  };
  HarmonicReport details;
  harmonic_coordinates(bar.mesh.V, bar.cage, binding, options, nullptr, &details);
  const long during = std::count_if(seen.begin(), seen.end(), [](double f) { return f > 0.02 && f < 0.9; });
  EXPECT_GE(during, 5) << "reports between the ordering and the solves";
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  int reports = 0;
  double asked_ms = -1;
  const Timer timer;
  binding.progress = [&](double fraction) {
    if (fraction <= 0.02 || ++reports < 3) return true;
    asked_ms = timer.ms();
    return false;
  };
  test::expect_error([&] { harmonic_coordinates(bar.mesh.V, bar.cage, binding, options); }, "cancelled",
                     ErrorCode::Cancelled);
  ASSERT_GE(asked_ms, 0.0);
  EXPECT_LT(timer.ms() - asked_ms, 100.0);
  std::printf("[ harmonic ] bar at 56: factor %.2f s, %ld reports during it, cancelled after %.0f ms\n",
              details.factor_seconds, during, asked_ms);
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
