// The voxel-dilated start surface: closed, manifold, outward, and at least `offset` from the mesh.
#include "core/cage/internal/voxel_dilation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "core/geometry/aabb_tree.h"
#include "core/error.h"
#include "core/mesh/shapes.h"

namespace sd {
namespace {

void expect_closed_oriented(const Mesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++directed[{m.F(f, k), m.F(f, (k + 1) % 3)}];
  for (const auto& [e, count] : directed) {
    ASSERT_EQ(count, 1);
    ASSERT_EQ(directed.count({e.second, e.first}), 1u);
  }
}

TEST(VoxelDilation, ClosedOutwardAndAtDistance) {
  // Two spheres close together (their gap is narrower than twice the offset, so they merge) and a box.
  Mesh mesh = make_icosphere(3, 1.0);
  for (const double offset : {0.05, 0.2}) {
    const Mesh surface = dilated_voxel_surface(mesh, offset, 0.08);
    expect_closed_oriented(surface);
    double volume = 0;
    for (int f = 0; f < surface.F.rows(); ++f)
      volume +=
          surface.V.row(surface.F(f, 0)).cross(surface.V.row(surface.F(f, 1))).dot(surface.V.row(surface.F(f, 2))) / 6;
    EXPECT_GT(volume, 4.18879);  // more than the unit ball
    // Every surface vertex is at least `offset` from the mesh (exact distance through the AABB tree).
    const AabbTree tree(triangle_boxes(mesh.V, mesh.F));
    double nearest = 1e300;
    for (int v = 0; v < surface.V.rows(); ++v)
      nearest = std::min(nearest, std::sqrt(squared_distance_to_triangles(tree, mesh, surface.V.row(v).transpose())));
    EXPECT_GE(nearest, offset);
    EXPECT_LT(nearest, offset + 2 * 0.08);  // and not much more
  }
}

TEST(VoxelDilation, WellComposedOnDiagonalContact) {
  // Two boxes touching along an edge only: the voxel union would be non-manifold there without the fix.
  Mesh a = make_box(1, 1, 1, 1), b = make_box(1, 1, 1, 1);
  b.V.col(0).array() += 1.0;
  b.V.col(1).array() += 1.0;
  Mesh both;
  both.V.resize(16, 3);
  both.V << a.V, b.V;
  both.F.resize(24, 3);
  both.F << a.F, (b.F.array() + 8).matrix();
  const Mesh surface = dilated_voxel_surface(both, 0.01, 0.1);
  expect_closed_oriented(surface);
  // Vertex-manifold: Euler characteristic of one closed genus-0 component.
  std::map<std::pair<int, int>, int> edges;
  for (int f = 0; f < surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int x = surface.F(f, k), y = surface.F(f, (k + 1) % 3);
      edges[{std::min(x, y), std::max(x, y)}]++;
    }
  EXPECT_EQ(surface.V.rows() - static_cast<long>(edges.size()) + surface.F.rows(), 2);
}

TEST(VoxelDilation, FarOffsetKeepsTheDistanceGuarantee) {
  // Ten voxels of offset: the candidates come from the distance transform far from the marked voxels.
  const Mesh mesh = make_icosphere(2, 1.0);
  const double offset = 1.0, h = 0.1;
  const Mesh surface = dilated_voxel_surface(mesh, offset, h);
  expect_closed_oriented(surface);
  const AabbTree tree(triangle_boxes(mesh.V, mesh.F));
  double nearest = 1e300, farthest = 0;
  for (int v = 0; v < surface.V.rows(); ++v) {
    const double d = std::sqrt(squared_distance_to_triangles(tree, mesh, surface.V.row(v).transpose()));
    nearest = std::min(nearest, d);
    farthest = std::max(farthest, d);
  }
  EXPECT_GE(nearest, offset);
  EXPECT_LT(farthest, offset + 2 * h);
}

// The message of the sd::Error `f` throws ("" if none).
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(VoxelDilation, RejectsBadParametersBeforeAllocating) {
  const Mesh mesh = make_icosphere(1, 1.0);
  EXPECT_THROW(dilated_voxel_surface(mesh, 0.0, 0.1), Error);
  EXPECT_THROW(dilated_voxel_surface(mesh, std::nan(""), 0.1), Error);
  // A grid far beyond int range is refused with its true size, not a wrapped-around negative count.
  const std::string tiny = error_of([&] { dilated_voxel_surface(mesh, 1e-12, 1e-12); });
  EXPECT_NE(tiny.find("over the limit of"), std::string::npos) << tiny;
  EXPECT_EQ(tiny.find('-'), std::string::npos) << tiny;
  const std::string far = error_of([&] { dilated_voxel_surface(mesh, 1e8, 0.1); });
  EXPECT_NE(far.find("over the limit of"), std::string::npos) << far;
  int calls = 0;
  const std::string cancelled =
      error_of([&] { dilated_voxel_surface(mesh, 0.1, 0.1, 64LL << 20, [&](double) { return ++calls < 2; }); });
  EXPECT_NE(cancelled.find("cancelled"), std::string::npos) << cancelled;
}

}  // namespace
}  // namespace sd
