// The 3-variable LP against brute-force vertex enumeration, and progressive hulls that must enclose what
// they started from.
#include "core/cage/internal/progressive_hull.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <random>

#include "core/mesh/shapes.h"
#include "core/error.h"

namespace sd {
namespace {

using Vec3 = Eigen::Vector3d;

// Minimum of c . x over the vertices of {n_i . x >= d_i} cut by the box |x_k| <= 1 (all triples of planes).
double brute_force(const std::vector<Vec3>& n, const std::vector<double>& d, const Vec3& c, bool& feasible) {
  std::vector<Vec3> N = n;
  std::vector<double> D = d;
  for (int k = 0; k < 3; ++k)
    for (double s : {1.0, -1.0}) {
      N.push_back(s * Vec3::Unit(k));
      D.push_back(-1.0);
    }
  double best = 1e300;
  feasible = false;
  for (size_t i = 0; i < N.size(); ++i)
    for (size_t j = i + 1; j < N.size(); ++j)
      for (size_t k = j + 1; k < N.size(); ++k) {
        Eigen::Matrix3d A;
        A << N[i].transpose(), N[j].transpose(), N[k].transpose();
        if (std::abs(A.determinant()) < 1e-9) continue;
        const Vec3 x = A.fullPivLu().solve(Vec3(D[i], D[j], D[k]));
        bool ok = true;
        for (size_t m = 0; m < N.size() && ok; ++m) ok = N[m].dot(x) >= D[m] - 1e-9;
        if (ok) {
          feasible = true;
          best = std::min(best, c.dot(x));
        }
      }
  return best;
}

TEST(ProgressiveHull, LinearProgramMatchesVertexEnumeration) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(-0.5, 0.3);
  int feasible_cases = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Vec3> n;
    std::vector<double> d;
    const int count = 3 + trial % 10;
    for (int i = 0; i < count; ++i) {
      n.push_back(Vec3(normal(rng), normal(rng), normal(rng)).normalized());
      d.push_back(uniform(rng));
    }
    const Vec3 c(normal(rng), normal(rng), normal(rng));
    bool feasible;
    const double expected = brute_force(n, d, c, feasible);
    Vec3 x;
    const bool solved = solve_lp3(n, d, c, x);
    ASSERT_EQ(solved, feasible) << "trial " << trial;
    if (!feasible) continue;
    ++feasible_cases;
    EXPECT_NEAR(c.dot(x), expected, 1e-7) << "trial " << trial;
  }
  EXPECT_GT(feasible_cases, 100);
}

TEST(ProgressiveHull, EachStageEnclosesTheStart) {
  const Mesh sphere = make_icosphere(3, 1.0);
  ProgressiveHullOptions options;
  options.tolerance = 1e-12;
  for (int target : {300, 100, 30}) {
    options.target_vertices = target;
    ProgressiveHullStats stats;
    const Mesh hull = progressive_hull(sphere, options, &stats);
    EXPECT_EQ(hull.V.rows(), target);
    EXPECT_EQ(stats.collapses, sphere.V.rows() - target);
    // Points just inside the start surface are inside the hull (solid-angle winding number 1).
    int outside = 0;
    for (int v = 0; v < sphere.V.rows(); ++v) {
      const Vec3 p = 0.999 * sphere.V.row(v).transpose();  // strictly inside the (star-shaped) start
      double w = 0;
      for (int f = 0; f < hull.F.rows(); ++f) {
        const Vec3 a = hull.V.row(hull.F(f, 0)).transpose() - p, b = hull.V.row(hull.F(f, 1)).transpose() - p,
                   c = hull.V.row(hull.F(f, 2)).transpose() - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        w += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
      }
      outside += std::abs(w / (4 * 3.14159265358979323846) - 1) > 1e-6;
    }
    EXPECT_EQ(outside, 0) << "target " << target;
  }
}

TEST(ProgressiveHull, CancelThrows) {
  const Mesh sphere = make_icosphere(4, 1.0);
  ProgressiveHullOptions options;
  options.target_vertices = 50;
  options.progress = [](double) { return false; };
  EXPECT_THROW(progressive_hull(sphere, options), Error);
}

}  // namespace
}  // namespace sd
