#include "core/mesh/mass_matrix.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/mesh/shapes.h"
#include "test_support.h"

namespace sd {
namespace {

double surface_area(const Mesh& m) {
  double area = 0;
  for (int f = 0; f < m.F.rows(); ++f)
    area += 0.5 * (m.V.row(m.F(f, 1)) - m.V.row(m.F(f, 0))).cross(m.V.row(m.F(f, 2)) - m.V.row(m.F(f, 0))).norm();
  return area;
}

TEST(MassMatrix, IsPositiveAndSumsToTheSurfaceArea) {
  for (const Mesh& mesh : {make_box(2, 3, 4, 3), make_icosphere(2, 1.5), make_torus(1.0, 0.3, 12, 8)}) {
    const Eigen::VectorXd mass = lumped_mass(mesh.V, mesh.F);
    ASSERT_EQ(mass.size(), mesh.V.rows());
    EXPECT_GT(mass.minCoeff(), 0.0);
    EXPECT_NEAR(mass.sum(), surface_area(mesh), 1e-12 * surface_area(mesh));
  }
  // The box's faces are 2x3, 2x4, 3x4: exact total 52.
  EXPECT_NEAR(lumped_mass(make_box(2, 3, 4, 1).V, make_box(2, 3, 4, 1).F).sum(), 52.0, 1e-12);
}

TEST(MassMatrix, RefusesAVertexWithoutArea) {
  Mesh mesh = make_box(1, 1, 1, 1);
  mesh.V.conservativeResize(mesh.V.rows() + 1, 3);
  mesh.V.row(mesh.V.rows() - 1) << 5, 5, 5;  // unreferenced
  test::expect_error([&] { lumped_mass(mesh.V, mesh.F); }, "vertex 8 has no area", ErrorCode::InvalidMesh);
}

}  // namespace
}  // namespace sd
