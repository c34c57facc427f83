#include "core/geometry/ray_caster.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "core/mesh/shapes.h"

namespace sd {
namespace {

// Every triangle tested, by Cramer's rule: the smallest t in (t_min, inf) and its triangle (-1: none).
std::pair<int, double> brute_force(const Mesh& mesh, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min,
                                   int skip) {
  std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
  for (int f = 0; f < mesh.F.rows(); ++f) {
    if (f == skip) continue;
    const Eigen::Vector3d p0 = mesh.V.row(mesh.F(f, 0)), e1 = mesh.V.row(mesh.F(f, 1)).transpose() - p0,
                          e2 = mesh.V.row(mesh.F(f, 2)).transpose() - p0, b = o - p0;
    const double det = -d.dot(e1.cross(e2));
    if (det == 0) continue;
    const double s = -d.dot(b.cross(e2)) / det, t = -d.dot(e1.cross(b)) / det, r = b.dot(e1.cross(e2)) / det;
    if (s >= 0 && t >= 0 && s + t <= 1 && r > t_min && r < best.second) best = {f, r};
  }
  return best;
}

TEST(RayCaster, FirstHitMatchesTestingEveryTriangle) {
  Mesh mesh = make_icosphere(3, 1.0);
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int j = 0; j < mesh.V.rows(); ++j) mesh.V.row(j) *= 0.7 + 0.5 * std::abs(normal(rng)) / 3;  // bumpy, concave
  const RayCaster caster(mesh);
  EXPECT_EQ(caster.size(), mesh.F.rows());
  int hits = 0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d o(0.6 * normal(rng), 0.6 * normal(rng), 0.6 * normal(rng));
    const Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    const int skip = k % 3 == 0 ? k % static_cast<int>(mesh.F.rows()) : -1;
    const auto expected = brute_force(mesh, o, d, 1e-9, skip);
    const RayHit hit = caster.first_hit(o, d, 1e-9, std::numeric_limits<double>::infinity(), skip);
    ASSERT_EQ(hit.face, expected.first) << "ray " << k;
    if (hit.face < 0) continue;
    ++hits;
    EXPECT_NEAR(hit.t, expected.second, 1e-12 * (1 + expected.second));
    // The barycentric coordinates locate the hit point on its triangle.
    const Eigen::Vector3d p0 = mesh.V.row(mesh.F(hit.face, 0)), p1 = mesh.V.row(mesh.F(hit.face, 1)),
                          p2 = mesh.V.row(mesh.F(hit.face, 2));
    EXPECT_LE(((1 - hit.u - hit.v) * p0 + hit.u * p1 + hit.v * p2 - (o + hit.t * d)).norm(), 1e-12);
  }
  EXPECT_GT(hits, 1000);
}

TEST(RayCaster, FaceTestsAndRegionsBoundTheQueries) {
  const Mesh box = make_box(2, 2, 2, 2);
  const RayCaster caster(box);
  RayHit hit;
  int crossed = 0;
  for (int f = 0; f < box.F.rows(); ++f)
    crossed += caster.intersect(f, Eigen::Vector3d(0.1, 0.2, 0.05), Eigen::Vector3d(1, 0, 0), 0, 10, hit);
  EXPECT_EQ(crossed, 1);  // the ray leaves the box once
  EXPECT_NEAR(hit.t, 0.9, 1e-15);
  EXPECT_FALSE(caster.intersect(hit.face, Eigen::Vector3d(0.1, 0.2, 0.05), Eigen::Vector3d(1, 0, 0), 0, 0.5, hit));
  // The half-space x >= 0.5 holds the triangles of the face x = 1 (and maybe others): a superset.
  std::vector<int> faces;
  caster.faces_in_region({{Eigen::Vector3d(1, 0, 0), 0.5}}, faces);
  for (int f = 0; f < box.F.rows(); ++f) {
    const bool on_right = box.V(box.F(f, 0), 0) == 1 && box.V(box.F(f, 1), 0) == 1 && box.V(box.F(f, 2), 0) == 1;
    const bool found = std::find(faces.begin(), faces.end(), f) != faces.end();
    if (on_right) EXPECT_TRUE(found) << f;
    const bool on_left = box.V(box.F(f, 0), 0) == -1 && box.V(box.F(f, 1), 0) == -1 && box.V(box.F(f, 2), 0) == -1;
    if (on_left) EXPECT_FALSE(found) << f;
  }
}

}  // namespace
}  // namespace sd
