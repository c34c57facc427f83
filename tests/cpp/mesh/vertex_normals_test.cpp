// Vertex normals for drawing (core/mesh/vertex_normals.h): area-weighted sums of the triangles' cross products,
// shared within smoothing groups, unit length, the same with any number of threads.
#include "core/mesh/vertex_normals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/mesh/shapes.h"
#include "core/parallel/thread_pool.h"
#include "test_support.h"

namespace sd {
namespace {

// The reference: per corner, the triangle's cross product added to its vertex's group, then normalised.
std::vector<float> reference(const Vertices& X, const Faces& F, const std::vector<int>& group) {
  int groups = 0;
  for (int g : group) groups = std::max(groups, g + 1);
  Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(groups, 3);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const Eigen::RowVector3d a = X.row(F(t, 0));
    const Eigen::RowVector3d n = (X.row(F(t, 1)) - a).cross(X.row(F(t, 2)) - a);
    for (int k = 0; k < 3; ++k) sums.row(group[F(t, k)]) += n;
  }
  std::vector<float> out(3 * group.size());
  for (size_t v = 0; v < group.size(); ++v)
    for (int d = 0; d < 3; ++d) out[3 * v + d] = static_cast<float>(sums(group[v], d) / sums.row(group[v]).norm());
  return out;
}

TEST(VertexNormals, SphereNormalsPointOutwardAndMatchTheReference) {
  const Mesh sphere = make_icosphere(3, 2.0);
  const VertexNormals normals(static_cast<int>(sphere.V.rows()), sphere.F, {}, {});
  std::vector<float> out;
  normals.compute(sphere.V, out);
  std::vector<int> own(static_cast<size_t>(sphere.V.rows()));
  for (size_t v = 0; v < own.size(); ++v) own[v] = static_cast<int>(v);
  EXPECT_EQ(out, reference(sphere.V, sphere.F, own));  // same sums in the same order: bit for bit
  for (Eigen::Index v = 0; v < sphere.V.rows(); ++v) {
    const Eigen::Vector3f n(out[3 * v], out[3 * v + 1], out[3 * v + 2]);
    EXPECT_NEAR(n.norm(), 1.0f, 1e-6f);
    EXPECT_GT(n.dot(sphere.V.row(v).transpose().cast<float>().normalized()), 0.99f) << "vertex " << v;
  }
}

TEST(VertexNormals, GroupsShareOneNormalAndLoneVerticesKeepTheirFallback) {
  // Two triangles folded along the edge 1-2, with vertex 4 a copy of vertex 1 (a seam): grouped with 1, both get
  // the sum of both triangles; vertex 5 is in no triangle and keeps its fallback; vertex 6 has none: zero.
  Vertices X(7, 3);
  X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1, 1, 0, 0, 5, 5, 5, 6, 6, 6;
  Faces F(2, 3);
  F << 0, 1, 2, 4, 3, 2;
  const std::vector<int> group = {0, 1, 2, 3, 1, 4, 5};
  std::vector<float> fallback(21, std::numeric_limits<float>::quiet_NaN());
  fallback[15] = 0.0f, fallback[16] = 0.0f, fallback[17] = 1.0f;
  const VertexNormals normals(7, F, group, fallback);
  std::vector<float> out;
  normals.compute(X, out);
  std::vector<float> expected = reference(X, F, group);
  expected[15] = 0.0f, expected[16] = 0.0f, expected[17] = 1.0f;  // the reference has no fallback: its 0/0
  expected[18] = expected[19] = expected[20] = 0.0f;
  EXPECT_EQ(out, expected);
  for (int d = 0; d < 3; ++d) EXPECT_EQ(out[3 + d], out[12 + d]) << "the seam's copies share one normal";
}

TEST(VertexNormals, TheSameWithAnyNumberOfThreads) {
  const Mesh capsule = make_capsule(4.0, 0.5, 20, 80, 160);  // 51k triangles: many blocks
  const VertexNormals normals(static_cast<int>(capsule.V.rows()), capsule.F, {}, {});
  std::vector<float> one, two;
  const int saved = parallel::threads();
  parallel::set_threads(1);
  normals.compute(capsule.V, one);
  parallel::set_threads(2);
  normals.compute(capsule.V, two);
  parallel::set_threads(saved);
  EXPECT_EQ(one, two);
}

TEST(VertexNormals, RefusesSizesThatDoNotFit) {
  Faces F(1, 3);
  F << 0, 1, 3;
  EXPECT_THROW(VertexNormals(3, F, {}, {}), Error);  // vertex 3 of 3
  F << 0, 1, 2;
  EXPECT_THROW(VertexNormals(3, F, {0, 1}, {}), Error);        // a group per vertex
  EXPECT_THROW(VertexNormals(3, F, {}, {0.0f, 0.0f}), Error);  // 3 fallback numbers per vertex
  const VertexNormals normals(3, F, {}, {});
  std::vector<float> out;
  EXPECT_THROW(normals.compute(Vertices::Zero(4, 3), out), Error);
}

// Group ids name at most one group per vertex: [0, n). A larger one used to size the per-group arrays from it
// (2^31 - 1 overflowed and wrote out of bounds; 1e9 asked for gigabytes); the message names the vertex.
TEST(VertexNormals, RefusesGroupIdsOutsideTheVertexRange) {
  Faces F(1, 3);
  F << 0, 1, 2;
  test::expect_error(
      [] {
        VertexNormals(3, Faces(0, 3), {0, 0, 2147483647}, {});
      },
      "normal groups: vertex 2 has group 2147483647, outside [0, 3)");
  test::expect_error([&] { VertexNormals(3, F, {0, 1000000000, 0}, {}); }, "vertex 1 has group 1000000000");
  test::expect_error([&] { VertexNormals(3, F, {0, 3, 0}, {}); }, "outside [0, 3)");
  test::expect_error([&] { VertexNormals(3, F, {-1, 0, 0}, {}); }, "vertex 0 has group -1");
  VertexNormals(3, F, {2, 2, 0}, {});  // the largest id is n - 1
}

}  // namespace
}  // namespace sd
