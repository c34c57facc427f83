// Warnings about a deformed result: folds counted only where the surface turns over (not under rigid motions or
// smooth bends), and a deformed cage that crosses itself.
#include "core/mesh/deformation_check.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "core/mesh/shapes.h"

namespace sd {
namespace {

const Finding* find(const std::vector<Finding>& findings, const std::string& code) {
  for (const Finding& f : findings)
    if (f.code == code) return &f;
  return nullptr;
}

TEST(DeformationCheck, RigidMotionsAndSmoothBendsFoldNothing) {
  const Mesh m = make_capsule(2.0, 0.4, 4, 8, 12);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2.5, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  const Vertices rotated = (m.V * R.transpose()).rowwise() + Eigen::RowVector3d(4, 5, 6);
  EXPECT_EQ(folded_triangles(m, rotated).folded_triangles, 0);
  Vertices bent = m.V;  // a quarter turn along the capsule's length
  for (int i = 0; i < bent.rows(); ++i) {
    const double a = 0.4 * m.V(i, 0);
    bent.row(i) = Eigen::RowVector3d(std::cos(a) * m.V(i, 0), std::sin(a) * m.V(i, 0) + m.V(i, 1), m.V(i, 2));
  }
  EXPECT_EQ(folded_triangles(m, bent).folded_triangles, 0);
  EXPECT_TRUE(check_deformation(m, bent, Mesh{}, Vertices(0, 3)).empty());
}

TEST(DeformationCheck, AVertexPushedThroughTheSurfaceFoldsItsTriangles) {
  const Mesh m = make_icosphere(2, 1.0);
  Vertices dent = m.V;
  dent.row(0) *= 0.2;  // a deep dent is not a fold: no triangle turns over
  EXPECT_EQ(folded_triangles(m, dent).folded_triangles, 0);
  Vertices X = m.V;
  X.row(0) *= -1.0;  // through the sphere to the other side: its fan turns over
  const FoldCount folds = folded_triangles(m, X);
  EXPECT_GE(folds.folded_triangles, 5);
  const auto findings = check_deformation(m, X, Mesh{}, Vertices(0, 3));
  ASSERT_NE(find(findings, "folded_triangles"), nullptr);
  EXPECT_EQ(find(findings, "folded_triangles")->severity, Severity::Warning);
  Vertices collapsed = m.V;
  collapsed.row(m.F(0, 1)) = collapsed.row(m.F(0, 0));  // two corners of face 0 meet
  EXPECT_GE(folded_triangles(m, collapsed).folded_triangles, 1);
}

TEST(DeformationCheck, DeformedCageThatCrossesItselfIsNamed) {
  const Mesh mesh = make_icosphere(1, 0.5);
  const Mesh cage = make_icosphere(1, 1.5);
  EXPECT_EQ(find(check_deformation(mesh, mesh.V, cage, cage.V), "cage_self_intersecting"), nullptr);
  Vertices P = cage.V;
  P.row(0) *= -1.6;  // through the opposite side
  const auto findings = check_deformation(mesh, mesh.V, cage, P);
  ASSERT_NE(find(findings, "cage_self_intersecting"), nullptr);
  EXPECT_NE(find(findings, "cage_self_intersecting")->message.find("pairs of its faces intersect"), std::string::npos);
}

}  // namespace
}  // namespace sd
