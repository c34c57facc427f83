#include "core/basis/positive_mean_value_coordinates.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/parallel/thread_pool.h"
#include "core/basis/mean_value_coordinates.h"
#include "test_support.h"
#include "basis/cage_fixtures.h"

namespace sd {
namespace {

// ---------------------------------------------------------------------------------------------------
// Reference, independent of the library's method (which integrates the front-facing triangles in closed form
// and samples only behind the back-facing ones): the definition integrated over the whole sphere on the
// paper's cube map. Each pixel (two spherical triangles) sends rays from x through its corners and centre; the
// first triangle each meets is found by testing every triangle. When all five meet the same triangle, the
// pixel's integral of that triangle's hat functions over 1/r is taken in closed form (its mean vector m =
// integral of the direction, and sum_k c_k (p_k - x) = m); otherwise the pixel is split in four, down to
// `depth` levels, where the centre's triangle takes the pixel.

// The first triangle the ray from x along d meets (-1: none).
int first_triangle(const Mesh& cage, const Eigen::Vector3d& x, const Eigen::Vector3d& d) {
  double best = std::numeric_limits<double>::infinity();
  int hit = -1;
  for (int f = 0; f < cage.F.rows(); ++f) {
    // x + r d = p0 + s (p1 - p0) + t (p2 - p0), by Cramer's rule.
    const Eigen::Vector3d p0 = cage.V.row(cage.F(f, 0)), e1 = cage.V.row(cage.F(f, 1)).transpose() - p0,
                          e2 = cage.V.row(cage.F(f, 2)).transpose() - p0, b = x - p0;
    const double det = -d.dot(e1.cross(e2));
    if (det == 0) continue;
    const double s = -d.dot(b.cross(e2)) / det, t = -d.dot(e1.cross(b)) / det, r = b.dot(e1.cross(e2)) / det;
    if (s >= 0 && t >= 0 && s + t <= 1 && r > 0 && r < best) {
      best = r;
      hit = f;
    }
  }
  return hit;
}

// Integral of the unit direction over the spherical triangle a, b, c (counter-clockwise seen from outside the
// sphere): 1/2 sum over its edges of the arc times the unit normal of the edge's great circle, pointing in.
Eigen::Vector3d mean_vector(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  const Eigen::Vector3d* v[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& p = *v[k];
    const Eigen::Vector3d& q = *v[(k + 1) % 3];
    m += 0.5 * std::atan2(p.cross(q).norm(), p.dot(q)) * p.cross(q).normalized();
  }
  return m;
}

void integrate_pixel(const Mesh& cage, const Eigen::Vector3d& x, const Eigen::Vector3d corner[4], int depth,
                     Eigen::VectorXd& w) {
  Eigen::Vector3d d[4];
  for (int k = 0; k < 4; ++k) d[k] = corner[k].normalized();
  const Eigen::Vector3d centre = (corner[0] + corner[1] + corner[2] + corner[3]) / 4;
  const int face = first_triangle(cage, x, centre);
  bool same = face >= 0;
  for (int k = 0; k < 4 && same; ++k)
    same = first_triangle(cage, x, d[k] * 0.999999 + centre.normalized() * 1e-6) == face;
  if (!same && depth > 0) {
    const Eigen::Vector3d mid[4] = {(corner[0] + corner[1]) / 2, (corner[1] + corner[2]) / 2,
                                    (corner[2] + corner[3]) / 2, (corner[3] + corner[0]) / 2};
    const Eigen::Vector3d quads[4][4] = {{corner[0], mid[0], centre, mid[3]},
                                         {mid[0], corner[1], mid[1], centre},
                                         {centre, mid[1], corner[2], mid[2]},
                                         {mid[3], centre, mid[2], corner[3]}};
    for (const auto& q : quads) integrate_pixel(cage, x, q, depth - 1, w);
    return;
  }
  if (face < 0) return;
  Eigen::Vector3d m = mean_vector(d[0], d[1], d[2]) + mean_vector(d[0], d[2], d[3]);
  if (d[0].cross(d[1]).dot(d[2]) < 0) m = -m;  // the pixel's corners run clockwise seen from outside
  Eigen::Matrix3d M;
  for (int k = 0; k < 3; ++k) M.col(k) = cage.V.row(cage.F(face, k)).transpose() - x;
  const Eigen::Vector3d c = M.colPivHouseholderQr().solve(m);
  for (int k = 0; k < 3; ++k) w[cage.F(face, k)] += c[k];
}

Eigen::VectorXd reference_pmvc(const Eigen::Vector3d& x, const Mesh& cage, int resolution, int depth) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(cage.V.rows());
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
    const double sign = face % 2 ? -1 : 1;
    for (int i = 0; i < resolution; ++i)
      for (int j = 0; j < resolution; ++j) {
        Eigen::Vector3d corner[4];
        const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
        for (int k = 0; k < 4; ++k) {
          corner[k][axis] = sign;
          corner[k][u] = -1 + 2.0 * (i + di[k]) / resolution;
          corner[k][v] = -1 + 2.0 * (j + dj[k]) / resolution;
        }
        integrate_pixel(cage, x, corner, depth, w);
      }
  }
  return w / w.sum();
}

// A spiky star: the icosahedron's 12 vertices at radius 1.5 and the 30 edge midpoints of its subdivision at
// 0.6. Star-shaped about the origin (closed, outward); from inside a spike most of the cage is hidden.
Mesh spiky_star() {
  Mesh cage = make_icosphere(1, 1.0);
  for (int j = 0; j < cage.V.rows(); ++j) cage.V.row(j) *= j < 12 ? 1.5 : 0.6;
  return cage;
}

// Points along random directions, at 60 to 95% of the distance from the origin to the cage: in the spikes.
Vertices star_points(const Mesh& cage, int count) {
  const Vertices directions = test::random_ball_points(count, 1.0, 17);
  Vertices points(directions.rows(), 3);
  for (int i = 0; i < directions.rows(); ++i) {
    const Eigen::Vector3d d = directions.row(i).normalized();
    const int face = first_triangle(cage, Eigen::Vector3d::Zero(), d);
    const Eigen::Vector3d p0 = cage.V.row(cage.F(face, 0)),
                          normal = (cage.V.row(cage.F(face, 1)).transpose() - p0)
                                       .cross(cage.V.row(cage.F(face, 2)).transpose() - p0);
    const double reach = normal.dot(p0) / normal.dot(d);
    points.row(i) = (0.6 + 0.35 * (i % 8) / 7.0) * reach * d.transpose();
  }
  return points;
}

Eigen::MatrixXd pmvc(const Vertices& points, const Mesh& cage, int resolution = 32,
                     PositiveMvcReport* sampling = nullptr, MvcReport* report = nullptr) {
  PositiveMvcOptions options;
  options.resolution = resolution;
  return positive_mean_value_coordinates(points, cage, {}, options, report, sampling).to_dense();
}

double max_row_sum_error(const Eigen::MatrixXd& W) { return (W.rowwise().sum().array() - 1.0).abs().maxCoeff(); }

// Points inside the L prism, in both arms and at the corner that sees everything.
Vertices l_points() {
  Vertices points(5, 3);
  points << 0.5, 0.5, 0.5, 1.6, 0.4, 0.3, 0.3, 1.7, 0.6, 0.9, 0.9, 0.5, 1.85, 0.85, 0.9;
  return points;
}

// ---------------------------------------------------------------------------------------------------

// A point inside a convex cage sees all of it: no triangle faces away, no ray is cast, and the definition is
// mean value coordinates'.
TEST(PositiveMeanValueCoordinates, EqualMeanValueCoordinatesInsideConvexCages) {
  for (const Mesh& cage : {make_icosphere(1, 1.0), make_box(2, 1, 1.5, 3)}) {
    const Vertices points = test::random_ball_points(200, 0.45, 3);
    PositiveMvcReport sampling;
    const Eigen::MatrixXd W = pmvc(points, cage, 32, &sampling);
    const Eigen::MatrixXd M = mean_value_coordinates(points, cage).to_dense();
    EXPECT_LE((W - M).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_EQ(sampling.rays, 0);
    EXPECT_EQ(sampling.hidden_faces, 0);
  }
}

TEST(PositiveMeanValueCoordinates, NonNegativeAndPartitionOfUnityInConcaveCages) {
  const test::BentBar bent = test::bent_bar();
  const struct {
    const char* name;
    Mesh cage;
    Vertices points;
  } cases[] = {{"star", spiky_star(), star_points(spiky_star(), 300)},
               {"L prism", test::l_prism(), l_points()},
               {"bent bar", bent.cage, bent.mesh.V}};
  for (const auto& c : cases) {
    MvcReport report;
    PositiveMvcReport sampling;
    const Eigen::MatrixXd W = pmvc(c.points, c.cage, 16, &sampling, &report);
    const Eigen::MatrixXd M = mean_value_coordinates(c.points, c.cage).to_dense();
    SCOPED_TRACE(c.name);
    EXPECT_GE(W.minCoeff(), 0.0);
    EXPECT_EQ(report.min_weight, W.minCoeff());
    EXPECT_LE(max_row_sum_error(W), 1e-13);
    EXPECT_LT(M.minCoeff(), -1e-3);  // the cage is concave where these points are: mean value weights go negative
    EXPECT_GT(sampling.rays, 0);
    std::printf("[ pmvc     ] %s: min weight %.3g (mvc %.3g), %.0f rays/point, %.1f hidden triangles/point\n", c.name,
                W.minCoeff(), M.minCoeff(), sampling.rays / c.points.rows(), sampling.hidden_faces / c.points.rows());
  }
}

// The definition, integrated independently by brute force over the sphere at a fine resolution, against the
// library at growing resolutions: the error falls as the resolution grows.
TEST(PositiveMeanValueCoordinates, ConvergesToTheSphereIntegralAsTheResolutionGrows) {
  for (const Mesh& cage : {test::l_prism(), spiky_star()}) {
    const Vertices points = cage.V.rows() == 12 ? l_points() : Vertices(star_points(cage, 4));
    std::vector<Eigen::VectorXd> reference;
    for (int i = 0; i < points.rows(); ++i) reference.push_back(reference_pmvc(points.row(i).transpose(), cage, 16, 4));
    double previous = std::numeric_limits<double>::infinity();
    for (int resolution : {4, 8, 16, 32}) {
      const Eigen::MatrixXd W = pmvc(points, cage, resolution);
      double error = 0;
      for (int i = 0; i < points.rows(); ++i)
        error = std::max(error, (W.row(i).transpose() - reference[i]).cwiseAbs().sum());
      std::printf("[ pmvc     ] %d-vertex cage, resolution %2d: largest row L1 difference from the reference %.2e\n",
                  int(cage.V.rows()), resolution, error);
      EXPECT_LT(error, previous * 1.05) << "resolution " << resolution;
      previous = error;
    }
    EXPECT_LT(previous, 4e-3);
  }
}

// What positivity costs: where a point does not see the whole cage, W P0 is not the point.
TEST(PositiveMeanValueCoordinates, LoseLinearPrecisionWhereTheCageIsHidden) {
  const test::BentBar bent = test::bent_bar();
  const Eigen::MatrixXd W = pmvc(bent.mesh.V, bent.cage, 16);
  const double error =
      ((W * bent.cage.V) - bent.mesh.V).rowwise().norm().maxCoeff() / bounding_box_diagonal(bent.cage.V);
  const double mvc_error = ((mean_value_coordinates(bent.mesh.V, bent.cage).to_dense() * bent.cage.V) - bent.mesh.V)
                               .rowwise()
                               .norm()
                               .maxCoeff() /
                           bounding_box_diagonal(bent.cage.V);
  std::printf("[ pmvc     ] bent bar: linear precision %.2e x cage diagonal (mvc %.1e)\n", error, mvc_error);
  EXPECT_LT(mvc_error, 1e-10);
  EXPECT_GT(error, 1e-4);
  EXPECT_LT(error, 0.2);
}

// Cells and rays are built from the cage's own geometry, so a similarity transform of points and cage gives
// the same weights to rounding.
TEST(PositiveMeanValueCoordinates, InvariantUnderSimilarityTransforms) {
  const Mesh cage = test::l_prism();
  const Vertices points = l_points();
  const Eigen::MatrixXd W = pmvc(points, cage, 12);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (double scale : {0.01, 250.0}) {
    Mesh moved = cage;
    Vertices moved_points = points;
    moved.V = (scale * cage.V * R.transpose()).rowwise() + Eigen::RowVector3d(5, -3, 2);
    moved_points = (scale * points * R.transpose()).rowwise() + Eigen::RowVector3d(5, -3, 2);
    EXPECT_LE((pmvc(moved_points, moved, 12) - W).cwiseAbs().maxCoeff(), 1e-9) << "scale " << scale;
  }
}

TEST(PositiveMeanValueCoordinates, ThreadCountsDoNotChangeTheResult) {
  const test::BentBar bent = test::bent_bar();
  const int saved = parallel::threads();
  parallel::set_threads(1);
  PositiveMvcReport one_sampling;
  const Eigen::MatrixXd one = pmvc(bent.mesh.V, bent.cage, 16, &one_sampling);
  for (int threads : {2, 4}) {
    parallel::set_threads(threads);
    PositiveMvcReport sampling;
    EXPECT_EQ((pmvc(bent.mesh.V, bent.cage, 16, &sampling) - one).cwiseAbs().maxCoeff(), 0.0) << threads << " threads";
    EXPECT_EQ(sampling.rays, one_sampling.rays);
  }
  parallel::set_threads(saved);
}

TEST(PositiveMeanValueCoordinates, RefusesBadInput) {
  const Mesh cage = test::l_prism();
  PositiveMvcOptions options;
  options.resolution = 1;
  test::expect_error([&] { positive_mean_value_coordinates(l_points(), cage, {}, options); }, "resolution must be",
                     ErrorCode::InvalidArgument);
  Vertices outside = l_points();
  outside.row(3) << 1.5, 1.5, 0.5;  // in the notch of the L
  test::expect_error([&] { positive_mean_value_coordinates(outside, cage, {}); }, "1 of 5 mesh vertices are outside",
                     ErrorCode::MeshOutsideCage);
  MvcOptions small;
  small.memory_budget_bytes = 100;
  test::expect_error([&] { positive_mean_value_coordinates(l_points(), cage, small); }, "over the memory budget",
                     ErrorCode::MemoryBudget);
}

TEST(PositiveMeanValueCoordinates, ReportsProgressAndCanBeCancelled) {
  const test::BentBar bent = test::bent_bar();
  test::expect_progress_and_cancel(
      [&](const MvcOptions& binding) { positive_mean_value_coordinates(bent.mesh.V, bent.cage, binding); });
}

// The goal on real cages: every weight >= 0 and rows summing to 1 within 1e-8.
class PositiveRealPairs : public ::testing::TestWithParam<test::SharedPair> {};

TEST_P(PositiveRealPairs, NonNegativeAndPartitionOfUnity) {
  const test::SharedPair pair = GetParam();
  SD_REQUIRE_SHARED_DATA(pair.mesh);
  SD_REQUIRE_SHARED_DATA(pair.cage);
  const Mesh mesh = test::load_shared_mesh(pair.mesh);
  const Mesh cage = test::load_shared_mesh(pair.cage);
  const Vertices points = test::subsampled_rows(mesh, pair.max_rows);
  MvcReport report;
  PositiveMvcReport sampling;
  const Eigen::MatrixXd W = pmvc(points, cage, 16, &sampling, &report);
  EXPECT_GE(W.minCoeff(), 0.0);
  EXPECT_LE(max_row_sum_error(W), 1e-8);
  std::printf("[ pair     ] %s + %s: %d rows, min weight %.3g, row-sum error %.1e, %.0f rays/point\n", pair.mesh,
              pair.cage, int(points.rows()), report.min_weight, max_row_sum_error(W), sampling.rays / points.rows());
}

INSTANTIATE_TEST_SUITE_P(SharedData, PositiveRealPairs,
                         ::testing::Values(test::SharedPair{"armadillo.obj", "armadillo_cage.obj", 1000},
                                           test::SharedPair{"gargoyle.obj", "gargoyle_cage.obj", 800},
                                           test::SharedPair{"handbones.obj", "handbones_cage_v172.obj", 500}),
                         test::shared_pair_name);

}  // namespace
}  // namespace sd
