#include "core/geometry/winding_number.h"

#include <gtest/gtest.h>

#include "core/mesh/shapes.h"

namespace sd {
namespace {

TEST(WindingNumber, InsideOutsideAndOnAFace) {
  const Mesh sphere = make_icosphere(2, 1.0);
  EXPECT_NEAR(winding_number(sphere, Eigen::RowVector3d(0.1, -0.2, 0.3)), 1.0, 1e-12);
  EXPECT_NEAR(winding_number(sphere, Eigen::RowVector3d(1.5, 0.2, 0.0)), 0.0, 1e-12);
  EXPECT_NEAR(winding_number(sphere, Eigen::RowVector3d(40, 50, -60)), 0.0, 1e-12);
  for (int f : {0, 7, 100}) {
    const Eigen::RowVector3d centroid =
        (sphere.V.row(sphere.F(f, 0)) + sphere.V.row(sphere.F(f, 1)) + sphere.V.row(sphere.F(f, 2))) / 3.0;
    EXPECT_NEAR(winding_number(sphere, centroid), 0.5, 1e-12) << "face " << f;
  }
  Mesh flipped = sphere;
  flipped.F.col(1).swap(flipped.F.col(2));
  EXPECT_NEAR(winding_number(flipped, Eigen::RowVector3d(0, 0, 0)), -1.0, 1e-12);
}

// The batched sum (series atan2, padded blocks) equals the exact one to well below the 1/2 threshold,
// for points inside, outside and near the surface of a mesh whose face count is not a multiple of the
// block size.
TEST(WindingNumber, BatchAgreesWithExact) {
  Mesh mesh = make_capsule(1.0, 0.6, 4, 2, 10);
  mesh.V.col(1) *= 1.7;  // not symmetric in y and z
  ASSERT_NE(mesh.F.rows() % 128, 0);
  const BatchWindingNumber batch(mesh);
  BatchWindingNumber::Scratch scratch;
  const Vertices points = Vertices::Random(500, 3) * 1.4;
  for (int i = 0; i < points.rows(); ++i) {
    const double exact = winding_number(mesh, points.row(i));
    EXPECT_NEAR(batch(points.row(i), scratch), exact, 1e-8 * static_cast<double>(mesh.F.rows())) << "point " << i;
  }
  Mesh flipped = mesh;
  flipped.F.col(1).swap(flipped.F.col(2));
  const BatchWindingNumber inward(flipped);
  EXPECT_NEAR(inward(Eigen::RowVector3d(0, 0, 0), scratch), -1.0, 1e-8);
}

}  // namespace
}  // namespace sd
