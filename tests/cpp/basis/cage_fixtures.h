// Cages and points shared by the tests of the cage coordinates (mean value, positive mean value, harmonic).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cctype>
#include <functional>
#include <vector>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "core/mesh/mesh.h"
#include "core/mesh/shapes.h"
#include "core/basis/mean_value_coordinates.h"
#include "test_support.h"

namespace sd::test {

// Uniform random points in the axis-aligned box [lo, hi].
inline Vertices random_points(int count, const Eigen::RowVector3d& lo, const Eigen::RowVector3d& hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Vertices points(count, 3);
  for (int i = 0; i < count; ++i)
    for (int a = 0; a < 3; ++a) points(i, a) = lo[a] + (hi[a] - lo[a]) * unit(rng);
  return points;
}

// Random points in the ball of `radius` at the origin.
inline Vertices random_ball_points(int count, double radius, unsigned seed) {
  Vertices cube =
      random_points(4 * count, Eigen::RowVector3d::Constant(-radius), Eigen::RowVector3d::Constant(radius), seed);
  Vertices points(count, 3);
  int kept = 0;
  for (int i = 0; i < cube.rows() && kept < count; ++i)
    if (cube.row(i).norm() < radius) points.row(kept++) = cube.row(i);
  return points.topRows(kept);
}

// A star-shaped, concave cage: an icosphere whose vertex radii vary between 0.6 and 1.3. Star-shaped
// about the origin, so it stays closed and outward; every point within 0.45 of the origin is inside.
inline Mesh star_cage() {
  Mesh cage = make_icosphere(1, 1.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> radius(0.6, 1.3);
  for (int j = 0; j < cage.V.rows(); ++j) cage.V.row(j) *= radius(rng);
  return cage;
}

// An L-shaped prism: the L (0,0) (2,0) (2,1) (1,1) (1,2) (0,2) extruded from z = 0 to z = 1. Concave,
// and the planes of the notch faces pass through its interior.
inline Mesh l_prism() {
  const double L[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  Mesh cage;
  cage.V.resize(12, 3);
  for (int i = 0; i < 6; ++i) {
    cage.V.row(i) << L[i][0], L[i][1], 0.0;
    cage.V.row(i + 6) << L[i][0], L[i][1], 1.0;
  }
  cage.F.resize(20, 3);
  int f = 0;
  for (int k = 1; k <= 4; ++k) {             // caps: fans from the corner (0, 0), which sees the whole L
    cage.F.row(f++) << 0, k + 1, k;          // bottom, normal -z
    cage.F.row(f++) << 6, 6 + k, 6 + k + 1;  // top, normal +z
  }
  for (int i = 0; i < 6; ++i) {  // sides: the L is counter-clockwise, so outward is to the right
    const int j = (i + 1) % 6;
    cage.F.row(f++) << i, j, j + 6;
    cage.F.row(f++) << i, j + 6, i + 6;
  }
  return cage;
}

// A capsule bent into a C (3/4 of a turn) inside its own bent box cage of 12 slabs: the cage is concave on the
// inside of the C, where its two arms face each other.
struct BentBar {
  Mesh mesh;
  Mesh cage;
};
inline BentBar bent_bar(int rings = 6, int cylinder_rings = 24, int segments = 24, int cage_segments = 12) {
  const double radius = 5.4 / (1.5 * 3.14159265358979323846);
  Mesh capsule = make_capsule(4.0, 0.5, rings, cylinder_rings, segments);
  Mesh cage = make_bar_cage(-2.7, 2.7, 0.7, 0.7, cage_segments);
  capsule.V = bend_along_x(capsule.V, radius);
  cage.V = bend_along_x(cage.V, radius);
  return {capsule, cage};
}

// A binding (bind(options) computes W) reports a rising fraction ending at 1, and throws Cancelled when the
// callback returns false half-way.
inline void expect_progress_and_cancel(const std::function<void(const MvcOptions&)>& bind) {
  MvcOptions binding;
  std::vector<double> seen;
  binding.progress = [&](double fraction) {
    seen.push_back(fraction);
    return true;
  };
  bind(binding);
  ASSERT_GE(seen.size(), 2u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), 1.0);
  binding.progress = [](double fraction) { return fraction < 0.5; };
  expect_error([&] { bind(binding); }, "binding cancelled", ErrorCode::Cancelled);
}

// A mesh and cage of ../shared/data; tests on large meshes use at most max_rows of its vertices.
struct SharedPair {
  const char* mesh;
  const char* cage;
  int max_rows = 1 << 30;
};

// Every k-th vertex of the mesh, k chosen so that at most max_rows remain (the binding is the same code for
// every row, so a subsample keeps the test time small).
inline Vertices subsampled_rows(const Mesh& mesh, int max_rows) {
  const int n = static_cast<int>(mesh.V.rows());
  const int stride = std::max(1, (n + max_rows - 1) / max_rows);
  Vertices points((n + stride - 1) / stride, 3);
  for (int i = 0, r = 0; i < n; i += stride) points.row(r++) = mesh.V.row(i);
  return points;
}

// The test name of a pair: its cage file, letters and digits only.
inline std::string shared_pair_name(const ::testing::TestParamInfo<SharedPair>& info) {
  std::string name = info.param.cage;
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

}  // namespace sd::test
