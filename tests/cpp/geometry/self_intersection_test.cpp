// Triangle intersection primitives on hand-built cases with known answers, and the mesh-level queries.
#include "core/geometry/self_intersection.h"

#include <gtest/gtest.h>

#include "core/mesh/shapes.h"

namespace sd {
namespace {

using Vec3 = Eigen::Vector3d;

TEST(SelfIntersection, SegmentThroughTriangle) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(segment_intersects_triangle(Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), a, b, c, 0));
  EXPECT_FALSE(segment_intersects_triangle(Vec3(0.8, 0.8, -1), Vec3(0.8, 0.8, 1), a, b, c, 0));   // misses
  EXPECT_FALSE(segment_intersects_triangle(Vec3(0.2, 0.2, 0.1), Vec3(0.2, 0.2, 1), a, b, c, 0));  // stops short
  // Stops 0.01 short: refused with tol 0.02, accepted with tol 0.
  EXPECT_TRUE(segment_intersects_triangle(Vec3(0.2, 0.2, 0.01), Vec3(0.2, 0.2, 1), a, b, c, 0.02));
}

TEST(SelfIntersection, CoplanarSegmentDecidedIn2D) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(segment_intersects_triangle(Vec3(-1, 0.2, 0), Vec3(1, 0.2, 0), a, b, c, 1e-12));
  EXPECT_FALSE(segment_intersects_triangle(Vec3(-1, 1.5, 0), Vec3(1, 1.5, 0), a, b, c, 1e-12));
  EXPECT_TRUE(segment_intersects_triangle(Vec3(0.1, 0.1, 0), Vec3(0.2, 0.1, 0), a, b, c, 1e-12));  // inside
}

TEST(SelfIntersection, TrianglePairs) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  // Crossing through the middle, then the same pair moved apart.
  EXPECT_TRUE(triangles_intersect(a, b, c, Vec3(0.2, 0.2, -1), Vec3(0.3, 0.2, 1), Vec3(0.2, 0.3, 1), 0));
  EXPECT_FALSE(triangles_intersect(a, b, c, Vec3(2.2, 0.2, -1), Vec3(2.3, 0.2, 1), Vec3(2.2, 0.3, 1), 0));
  // Coplanar overlap and coplanar containment.
  EXPECT_TRUE(triangles_intersect(a, b, c, Vec3(0.5, 0.5, 0), Vec3(-0.5, 0.2, 0), Vec3(0.2, -0.5, 0), 1e-12));
  EXPECT_TRUE(triangles_intersect(a, b, c, Vec3(0.1, 0.1, 0), Vec3(0.2, 0.1, 0), Vec3(0.1, 0.2, 0), 1e-12));
}

TEST(SelfIntersection, SharedVertexAndFold) {
  Vertices V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, 1, 0.2, 0.2, -1;
  // Faces sharing vertex 0 only: (0,1,2) and (0,3,4) - the segment 3-4 pierces (0,1,2).
  EXPECT_TRUE(faces_intersect(V, Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(0, 3, 4), 0));
  V.row(4) << 0.2, 0.2, 0.5;  // now both above: they only touch at vertex 0
  EXPECT_FALSE(faces_intersect(V, Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(0, 3, 4), 0));
  // Sharing edge 0-1: folded flat onto each other vs. a right angle.
  Vertices W(4, 3);
  W << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, 1, 0;
  // (1,0,3) with 3 = (0.5,1,0) lies on top of (0,1,2) with the opposite normal.
  EXPECT_TRUE(faces_intersect(W, Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(1, 0, 3), 0));
  W.row(3) << 0.5, 0, 1;
  EXPECT_FALSE(faces_intersect(W, Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(1, 0, 3), 0));
}

TEST(SelfIntersection, MeshQueries) {
  const Mesh sphere = make_icosphere(2, 1.0);
  EXPECT_TRUE(self_intersections(sphere, 1e-12).empty());
  // Two spheres: apart, then overlapping.
  Mesh other = make_icosphere(2, 1.0);
  other.V.col(0).array() += 3.0;
  EXPECT_TRUE(surface_crossings(sphere, other, 1e-12).empty());
  other.V.col(0).array() -= 2.0;
  EXPECT_FALSE(surface_crossings(sphere, other, 1e-12).empty());
  // A box with one vertex pushed through the opposite face intersects itself.
  Mesh box = make_box(1, 1, 1, 2);
  int top = 0;
  for (int v = 0; v < box.V.rows(); ++v)
    if (box.V(v, 2) > 0.49 && std::abs(box.V(v, 0)) < 1e-9 && std::abs(box.V(v, 1)) < 1e-9) top = v;
  box.V(top, 2) = -1.0;
  EXPECT_FALSE(self_intersections(box, 1e-12).empty());
}

}  // namespace
}  // namespace sd
