#include "core/basis/mean_value_coordinates.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/error.h"
#include "core/parallel/thread_pool.h"
#include "core/mesh/shapes.h"
#include "core/timer.h"
#include "test_support.h"
#include "basis/cage_fixtures.h"

namespace sd {
double mvc_atan2_nonnegative_for_test(double y, double x);  // defined in mean_value_coordinates.cpp

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------------
// Reference: a slow, direct transcription of the vector form of 3D mean value coordinates (Floater,
// Kos and Reimers 2005; Ju et al. 2005 eq. 9-11), written independently of the library's formula:
// for each triangle, the integral of the unit vector over its spherical projection is
// m = 1/2 sum_k theta_k n_k (n_k the unit normal of the great circle through the edge opposite vertex k,
// theta_k that edge's arc), and the triangle's weights lambda solve [u0 u1 u2] lambda = m, i.e.
// lambda_k = (m . n_k) / (u_k . n_k). Vertex j then gets sum over its triangles lambda_k / d_j.
// Valid for generic points only (no on-face or in-plane handling).
Eigen::VectorXd reference_mvc(const Eigen::Vector3d& x, const Mesh& cage) {
  const int m = static_cast<int>(cage.V.rows());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m);
  for (int t = 0; t < cage.F.rows(); ++t) {
    Eigen::Vector3d u[3];
    double d[3];
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d v = cage.V.row(cage.F(t, k)).transpose() - x;
      d[k] = v.norm();
      u[k] = v / d[k];
    }
    Eigen::Vector3d n[3];
    double theta[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& a = u[(k + 1) % 3];
      const Eigen::Vector3d& b = u[(k + 2) % 3];
      Eigen::Vector3d c = a.cross(b);
      theta[k] = std::atan2(c.norm(), a.dot(b));
      n[k] = c.normalized();
    }
    Eigen::Vector3d mean = 0.5 * (theta[0] * n[0] + theta[1] * n[1] + theta[2] * n[2]);
    for (int k = 0; k < 3; ++k) w[cage.F(t, k)] += mean.dot(n[k]) / u[k].dot(n[k]) / d[k];
  }
  return w / w.sum();
}

// ---------------------------------------------------------------------------------------------------
// Fixtures.

using test::l_prism;
using test::random_ball_points;
using test::random_points;
using test::star_cage;

double max_row_sum_error(const Eigen::MatrixXd& W) { return (W.rowwise().sum().array() - 1.0).abs().maxCoeff(); }

// max_i |(W P0)_i - x_i|
double max_reproduction_error(const Eigen::MatrixXd& W, const Mesh& cage, const Vertices& points) {
  Eigen::MatrixXd reproduced = W * cage.V;
  return (reproduced - Eigen::MatrixXd(points)).rowwise().norm().maxCoeff();
}

// Checks partition of unity (1e-12) and linear precision (1e-10 x bbox diagonal) of W for points in cage.
void expect_exact_properties(const Vertices& points, const Mesh& cage, const std::string& what) {
  BasisMatrix W = mean_value_coordinates(points, cage);
  Eigen::MatrixXd dense = W.to_dense();
  const double diagonal = bounding_box_diagonal(points);
  EXPECT_LE(max_row_sum_error(dense), 1e-12) << what;
  EXPECT_LE(max_reproduction_error(dense, cage, points), 1e-10 * diagonal) << what;
}

// ---------------------------------------------------------------------------------------------------

TEST(MeanValueCoordinates, FastArctangentMatchesLibm) {
  double worst = 0;
  for (int i = 0; i <= 200000; ++i) {
    const double angle = (kPi / 2) * i / 200000.0;
    const double y = std::sin(angle), x = std::cos(angle);
    const double expected = std::atan2(y, x);
    worst = std::max(worst, std::abs(mvc_atan2_nonnegative_for_test(y, x) - expected) / std::max(expected, 1e-300));
  }
  EXPECT_LE(worst, 4.5e-16);  // about 2 ulps
  EXPECT_EQ(mvc_atan2_nonnegative_for_test(0.0, 1.0), 0.0);
  EXPECT_NEAR(mvc_atan2_nonnegative_for_test(1.0, 0.0), kPi / 2, 1e-16);
}

TEST(MeanValueCoordinates, PartitionOfUnityAndLinearPrecisionOnProceduralCages) {
  expect_exact_properties(random_points(400, {-0.99, -0.99, -0.99}, {0.99, 0.99, 0.99}, 1), make_box(2, 2, 2, 3),
                          "box");
  expect_exact_properties(random_ball_points(400, 0.9, 2), make_icosphere(2, 1.0), "icosphere");
  expect_exact_properties(random_ball_points(400, 0.45, 3), star_cage(), "star (concave)");
  expect_exact_properties(make_capsule(2.0, 0.3, 6, 10, 16).V, make_bar_cage(-1.5, 1.5, 0.5, 0.5, 6),
                          "capsule in bar cage");
}

TEST(MeanValueCoordinates, PositiveInsideConvexCages) {
  MvcReport report;
  mean_value_coordinates(random_points(300, {-0.99, -0.99, -0.99}, {0.99, 0.99, 0.99}, 4), make_box(2, 2, 2, 2), {},
                         &report);
  EXPECT_GT(report.min_weight, 0.0);
  mean_value_coordinates(random_ball_points(300, 0.95, 5), make_icosphere(1, 1.0), {}, &report);
  EXPECT_GT(report.min_weight, 0.0);
}

TEST(MeanValueCoordinates, ConcaveCageReportsNegativeMinimum) {
  // Points at the ends of the L's arms see the other arm's far vertices through the notch's reflex
  // edge, from behind: those weights are negative (mean value coordinates are not positive in
  // non-convex cages).
  Mesh cage = l_prism();
  Vertices points(4, 3);
  points << 1.9, 0.1, 0.5, 0.1, 1.9, 0.5, 1.5, 0.5, 0.5, 0.5, 0.5, 0.5;
  MvcReport report;
  BasisMatrix W = mean_value_coordinates(points, cage, {}, &report);
  Eigen::MatrixXd dense = W.to_dense();
  EXPECT_LT(report.min_weight, 0.0);
  EXPECT_EQ(report.min_weight, dense.minCoeff());
  EXPECT_EQ(dense(report.min_weight_row, report.min_weight_col), report.min_weight);
}

TEST(MeanValueCoordinates, AgreesWithReferenceImplementation) {
  struct Case {
    Mesh cage;
    Vertices points;
    const char* name;
  };
  std::vector<Case> cases = {
      {make_box(2, 2, 2, 2), random_points(150, {-0.95, -0.95, -0.95}, {0.95, 0.95, 0.95}, 8), "box"},
      {make_icosphere(1, 1.0), random_ball_points(150, 0.9, 9), "icosphere"},
      {star_cage(), random_ball_points(150, 0.45, 10), "star"},
      {l_prism(), random_points(150, {0.05, 0.05, 0.05}, {0.95, 1.95, 0.95}, 18), "L prism"},
  };
  for (const Case& c : cases) {
    Eigen::MatrixXd W = mean_value_coordinates(c.points, c.cage).to_dense();
    double worst = 0;
    for (int i = 0; i < c.points.rows(); ++i)
      worst = std::max(
          worst, (W.row(i).transpose() - reference_mvc(c.points.row(i).transpose(), c.cage)).cwiseAbs().maxCoeff());
    EXPECT_LE(worst, 1e-10) << c.name;
  }
}

TEST(MeanValueCoordinates, DeltaWeightsAtCageVertices) {
  Mesh cage = star_cage();
  MvcReport report;
  Eigen::MatrixXd W = mean_value_coordinates(cage.V, cage, {}, &report).to_dense();
  EXPECT_EQ(report.on_vertex, cage.V.rows());
  EXPECT_EQ((W - Eigen::MatrixXd::Identity(cage.V.rows(), cage.V.rows())).cwiseAbs().maxCoeff(), 0.0);
}

// Points approaching the interior of a cage triangle along its inward normal: the weights converge to
// the triangle's barycentric coordinates (others to 0), with error shrinking with the distance; on the
// triangle itself they are the barycentric coordinates.
TEST(MeanValueCoordinates, ContinuousTowardAFace) {
  Mesh cage = make_icosphere(1, 1.0);
  const int t = 5;
  const Eigen::Vector3d a = cage.V.row(cage.F(t, 0)), b = cage.V.row(cage.F(t, 1)), c = cage.V.row(cage.F(t, 2));
  const Eigen::Vector3d bary(0.2, 0.3, 0.5);
  const Eigen::Vector3d on_face = bary[0] * a + bary[1] * b + bary[2] * c;
  const Eigen::Vector3d inward = -(b - a).cross(c - a).normalized();
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(cage.V.rows());
  for (int k = 0; k < 3; ++k) expected[cage.F(t, k)] = bary[k];
  double previous = 1.0;
  for (double distance : {1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14}) {
    Vertices p(1, 3);
    p.row(0) = (on_face + distance * inward).transpose();
    const double error =
        (mean_value_coordinates(p, cage).to_dense().row(0).transpose() - expected).cwiseAbs().maxCoeff();
    EXPECT_LE(error, 50 * distance + 1e-13) << "distance " << distance;
    EXPECT_LE(error, previous + 1e-13) << "distance " << distance;
    previous = error;
  }
  Vertices p(1, 3);
  p.row(0) = on_face.transpose();
  MvcReport report;
  const Eigen::VectorXd w = mean_value_coordinates(p, cage, {}, &report).to_dense().row(0).transpose();
  EXPECT_LE((w - expected).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(report.on_face, 1);
}

// Points exactly on a cage edge interpolate linearly between its two end points.
TEST(MeanValueCoordinates, PointsOnAnEdgeInterpolateItsEndPoints) {
  Mesh cage = make_icosphere(1, 1.0);
  const int a = cage.F(3, 0), b = cage.F(3, 1);
  for (double s : {0.5, 0.25, 0.9}) {
    Vertices p(1, 3);
    p.row(0) = (1 - s) * cage.V.row(a) + s * cage.V.row(b);
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(cage.V.rows());
    expected[a] = 1 - s;
    expected[b] = s;
    EXPECT_LE((mean_value_coordinates(p, cage).to_dense().row(0).transpose() - expected).cwiseAbs().maxCoeff(), 1e-12)
        << "s " << s;
  }
}

// Points in the plane of a cage triangle but outside it: in an L-shaped prism the planes of the notch's
// faces (y = 1 and x = 1) cut through the interior. Those triangles contribute nothing there, and the
// weights are continuous across the plane.
TEST(MeanValueCoordinates, PointsInThePlaneOfCageTrianglesOutsideThem) {
  const Mesh cage = l_prism();
  Vertices points(6, 3);
  points << 0.5, 1.0, 0.5, 0.25, 1.0, 0.75, 1.0, 0.5, 0.5, 1.0, 0.2, 0.1, 0.999, 1.0, 0.5, 1e-3, 1.0, 0.5;
  expect_exact_properties(points, cage, "L prism, points in the notch planes");
  Eigen::MatrixXd on_plane = mean_value_coordinates(points, cage).to_dense();
  for (double offset : {1e-6, -1e-6, 1e-9, -1e-9}) {
    Vertices moved = points;
    moved.col(1).array() += offset;
    Eigen::MatrixXd near = mean_value_coordinates(moved, cage).to_dense();
    EXPECT_LE((near - on_plane).cwiseAbs().maxCoeff(), 100 * std::abs(offset)) << "offset " << offset;
  }
}

// A closed cage containing a zero-area triangle (a vertex inserted on an edge, with the T-junction closed
// by a degenerate triangle) gives the same coordinates as the cage without the extra vertex.
TEST(MeanValueCoordinates, DegenerateCageTrianglesAreSkipped) {
  Mesh cage = make_icosphere(1, 1.0);
  const int t = 0;
  const int a = cage.F(t, 0), b = cage.F(t, 1), c = cage.F(t, 2);
  const int p = static_cast<int>(cage.V.rows());
  Mesh split = cage;
  split.V.conservativeResize(p + 1, 3);
  split.V.row(p) = 0.5 * (cage.V.row(a) + cage.V.row(b));
  split.F.conservativeResize(cage.F.rows() + 2, 3);
  split.F.row(t) << a, p, c;
  split.F.row(cage.F.rows()) << p, b, c;
  split.F.row(cage.F.rows() + 1) << a, b, p;  // zero area
  Vertices points = random_ball_points(100, 0.9, 11);
  Eigen::MatrixXd W = mean_value_coordinates(points, cage).to_dense();
  Eigen::MatrixXd Ws = mean_value_coordinates(points, split).to_dense();
  expect_exact_properties(points, split, "cage with a degenerate triangle");
  // The new vertex sits on an edge, so its weight can be folded back onto the edge's end points.
  Eigen::MatrixXd folded = Ws.leftCols(p);
  folded.col(a) += 0.5 * Ws.col(p);
  folded.col(b) += 0.5 * Ws.col(p);
  // Not identical (the split changes the face through which the point sees the cage), only both valid:
  // partition of unity and linear precision (above) and both positive (convex).
  EXPECT_GT(W.minCoeff(), 0.0);
  EXPECT_GT(folded.minCoeff(), 0.0);
  // Points on the degenerate triangle's line (on edge a-b) still interpolate a and b.
  Vertices on_edge(1, 3);
  on_edge.row(0) = 0.75 * cage.V.row(a) + 0.25 * cage.V.row(b);
  Eigen::RowVectorXd w = mean_value_coordinates(on_edge, split).to_dense().row(0);
  EXPECT_NEAR(w * split.V.col(0), on_edge(0, 0), 1e-12);
  EXPECT_NEAR(w.sum(), 1.0, 1e-12);
}

TEST(MeanValueCoordinates, InvariantUnderSimilarityTransforms) {
  Mesh cage = star_cage();
  Vertices points = random_ball_points(120, 0.45, 12);
  Eigen::MatrixXd W = mean_value_coordinates(points, cage).to_dense();
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  const Eigen::RowVector3d shift(3.5, -2.0, 10.0);
  for (double scale : {1.0, 0.01, 250.0}) {
    Mesh moved = cage;
    moved.V = (scale * cage.V * rotation.transpose()).rowwise() + shift;
    Vertices moved_points = (scale * points * rotation.transpose()).rowwise() + shift;
    Eigen::MatrixXd Wm = mean_value_coordinates(moved_points, moved).to_dense();
    EXPECT_LE((Wm - W).cwiseAbs().maxCoeff(), 1e-11) << "scale " << scale;
  }
}

// float32 storage: the products differ from float64 storage by the rounding of W (~6e-8 relative per
// entry), and linear precision degrades to ~1e-7 of the cage size (documented in docs/mvc.md).
TEST(MeanValueCoordinates, Float32StorageAccuracy) {
  Mesh cage = make_box(3.4, 1.4, 1.4, 5);
  Vertices points = make_capsule(2.0, 0.45, 8, 20, 24).V;
  MvcOptions single;
  single.single_precision = true;
  BasisMatrix W64 = mean_value_coordinates(points, cage);
  BasisMatrix W32 = mean_value_coordinates(points, cage, single);
  EXPECT_EQ(W32.bytes() * 2, W64.bytes());
  Eigen::MatrixXd P = cage.V, out64, out32;
  W64.multiply(P, out64);
  W32.multiply(P, out32);
  const double diagonal = bounding_box_diagonal(points);
  const double product_error = (out32 - out64).cwiseAbs().maxCoeff() / out64.cwiseAbs().maxCoeff();
  EXPECT_LE(product_error, 1e-6);
  const double reproduction32 = max_reproduction_error(W32.to_dense(), cage, points) / diagonal;
  const double row_sum32 = max_row_sum_error(W32.to_dense());
  EXPECT_LE(reproduction32, 1e-6);
  EXPECT_LE(row_sum32, 1e-6);
  std::printf("[ float32  ] product rel. error %.2e, linear precision %.2e x bbox diagonal, row sums %.2e\n",
              product_error, reproduction32, row_sum32);
}

TEST(MeanValueCoordinates, RefusesOverTheMemoryBudget) {
  MvcOptions options;
  options.memory_budget_bytes = 1000;  // 1 kB
  Vertices points = random_ball_points(50, 0.5, 13);
  Mesh cage = make_icosphere(1, 1.0);  // 42 vertices: 50 x 42 x 8 = 16800 bytes
  try {
    mean_value_coordinates(points, cage, options);
    FAIL() << "expected the budget to be refused";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.code(), ErrorCode::MemoryBudget);
    EXPECT_NE(message.find("0.02 MB"), std::string::npos) << message;
    EXPECT_NE(message.find("coarser cage"), std::string::npos) << message;
    EXPECT_NE(message.find("float32"), std::string::npos) << message;
  }
  options.memory_budget_bytes = 50 * 42 * 4;
  options.single_precision = true;
  EXPECT_NO_THROW(mean_value_coordinates(points, cage, options));
}

// "raise the budget" only while that could help: a W larger than one allocation of the build can have
// (kMaxAllocationBytes: under 2 GiB in wasm, what size_t holds natively) is told so instead.
TEST(MeanValueCoordinates, TheBudgetMessageSuggestsRaisingItOnlyWhenThatCouldHelp) {
  MvcOptions options;
  options.memory_budget_bytes = 1000;
  test::expect_error([&] { check_weights_budget(50, 42, options); }, ", or raise the budget", ErrorCode::MemoryBudget);
  options.memory_budget_bytes = std::numeric_limits<size_t>::max();
  const int huge = std::numeric_limits<int>::max();  // W of 2^31 x 2^31 float64 is more than any size_t holds
  test::expect_error([&] { check_weights_budget(huge, huge, options); }, "(no budget helps: W is larger than the ",
                     ErrorCode::MemoryBudget);
  try {
    check_weights_budget(huge, huge, options);
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("raise the budget"), std::string::npos) << e.what();
  }
}

TEST(MeanValueCoordinates, NamesPointsOutsideTheCage) {
  Mesh cage = make_box(2, 2, 2, 2);
  Vertices points = random_points(20, {-0.9, -0.9, -0.9}, {0.9, 0.9, 0.9}, 14);
  points.row(3) << 1.5, 0, 0;
  points.row(11) << 0, 0, -1.0001;
  points.row(17) << 10, 10, 10;
  try {
    mean_value_coordinates(points, cage);
    FAIL() << "expected outside points to be refused";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.code(), ErrorCode::MeshOutsideCage);
    EXPECT_NE(message.find("3 of 20"), std::string::npos) << message;
    EXPECT_NE(message.find("3, 11, 17"), std::string::npos) << message;
  }
  // An inside-out cage makes every point "outside".
  Mesh flipped = cage;
  flipped.F.col(1).swap(flipped.F.col(2));
  EXPECT_THROW(mean_value_coordinates(random_points(5, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}, 15), flipped), Error);
}

TEST(MeanValueCoordinates, ReportsProgressAndCanBeCancelled) {
  Mesh cage = make_box(2, 2, 2, 1);
  Vertices points = random_points(2000, {-0.9, -0.9, -0.9}, {0.9, 0.9, 0.9}, 16);
  std::vector<double> fractions;
  MvcOptions options;
  options.progress = [&](double f) {
    fractions.push_back(f);
    return true;
  };
  mean_value_coordinates(points, cage, options);
  ASSERT_GE(fractions.size(), 3u);
  EXPECT_EQ(fractions.back(), 1.0);
  for (size_t k = 1; k < fractions.size(); ++k) EXPECT_GT(fractions[k], fractions[k - 1]);
  int calls = 0;
  options.progress = [&](double) { return ++calls < 2; };
  try {
    mean_value_coordinates(points, cage, options);
    FAIL() << "expected cancellation";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "binding cancelled");
    EXPECT_EQ(e.code(), ErrorCode::Cancelled);
  }
}

// Blocks of rows run on the thread pool and the progress callback splits them into chunks per thread count:
// neither changes W or the report.
TEST(MeanValueCoordinates, ThreadsAndProgressChunksDoNotChangeTheResult) {
  const Mesh cage = make_box(2, 2, 2, 2);
  const Vertices points = random_points(3000, {-0.9, -0.9, -0.9}, {0.9, 0.9, 0.9}, 21);
  const int saved = parallel::threads();
  parallel::set_threads(1);
  MvcReport plain_report;
  const Eigen::MatrixXd plain = mean_value_coordinates(points, cage, {}, &plain_report).to_dense();
  for (int threads : {2, 3}) {
    parallel::set_threads(threads);
    MvcOptions options;
    options.progress = [](double) { return true; };
    MvcReport report;
    EXPECT_TRUE(mean_value_coordinates(points, cage, options, &report).to_dense() == plain) << threads;
    EXPECT_EQ(report.min_weight, plain_report.min_weight) << threads;
    EXPECT_EQ(report.min_weight_row, plain_report.min_weight_row) << threads;
  }
  parallel::set_threads(saved);
}

TEST(MeanValueCoordinates, CancelAtTheLastProgressCallIsHonoured) {
  // 100 rows get a single progress call (at the end): returning false there must still cancel.
  Mesh cage = make_box(2, 2, 2, 1);
  MvcOptions options;
  int calls = 0;
  options.progress = [&](double) {
    ++calls;
    return false;
  };
  try {
    mean_value_coordinates(random_points(100, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}, 18), cage, options);
    FAIL() << "expected cancellation";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::Cancelled);  // as every other cancel: JS sees a CancelledError
  }
  EXPECT_EQ(calls, 1);
}

TEST(MeanValueCoordinates, RejectsBadCageIndices) {
  Mesh cage = make_box(2, 2, 2, 1);
  cage.F(4, 1) = 99;
  EXPECT_THROW(mean_value_coordinates(random_points(3, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}, 17), cage), Error);
}

// ---------------------------------------------------------------------------------------------------
// The real mesh + cage pairs of ../shared/data. Large meshes are subsampled (every k-th vertex) to keep
// the test time small; the binding itself is the same code for every row.

using Pair = test::SharedPair;

class RealPairs : public ::testing::TestWithParam<Pair> {};

TEST_P(RealPairs, PartitionOfUnityAndLinearPrecision) {
  const Pair pair = GetParam();
  SD_REQUIRE_SHARED_DATA(pair.mesh);
  SD_REQUIRE_SHARED_DATA(pair.cage);
  const Mesh mesh = test::load_shared_mesh(pair.mesh);
  const Mesh cage = test::load_shared_mesh(pair.cage);
  const int n = static_cast<int>(mesh.V.rows());
  const Vertices points = test::subsampled_rows(mesh, pair.max_rows);
  MvcReport report;
  const Timer timer;
  BasisMatrix W = mean_value_coordinates(points, cage, {}, &report);
  const double ms = timer.ms();
  Eigen::MatrixXd dense = W.to_dense();
  const double diagonal = bounding_box_diagonal(mesh.V);
  const double sum_error = max_row_sum_error(dense);
  const double reproduction = max_reproduction_error(dense, cage, points) / diagonal;
  EXPECT_LE(sum_error, 1e-12);
  EXPECT_LE(reproduction, 1e-10);
  std::printf(
      "[ pair     ] %s + %s: %d of %d vertices x %d cage vertices, %.0f ms, min weight %.4g, "
      "row-sum error %.1e, linear precision %.1e x bbox diagonal\n",
      pair.mesh, pair.cage, int(points.rows()), n, int(cage.V.rows()), ms, report.min_weight, sum_error, reproduction);
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealPairs,
                         ::testing::Values(Pair{"gargoyle.obj", "gargoyle_cage.obj", 3000},
                                           Pair{"gargoyle.obj", "gargoyle_cage_v27.obj", 3000},
                                           Pair{"armadillo.obj", "armadillo_cage.obj", 4000},
                                           Pair{"armadillo.obj", "armadillo_cage_v252.obj", 2000},
                                           Pair{"moomoo.obj", "moomoo_cage.obj", 2000},
                                           Pair{"handbones.obj", "handbones_cage.obj", 2000},
                                           Pair{"handbones.obj", "handbones_cage_v172.obj", 2000},
                                           Pair{"cow.obj", "cow_cage.obj", 4000}, Pair{"boy.obj", "boy_cage.obj", 1500},
                                           Pair{"spikybox.obj", "spikybox_cage.obj", 8000},
                                           Pair{"wiresphere.obj", "wiresphere_cage.obj", 8000}),
                         test::shared_pair_name);

}  // namespace
}  // namespace sd
