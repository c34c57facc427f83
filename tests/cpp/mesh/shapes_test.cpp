#include "core/mesh/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

namespace sd {
namespace {

// Signed volume by the divergence theorem, independent of core/volume so this test stands alone.
double enclosed_volume(const Mesh& m) {
  double v = 0;
  for (int f = 0; f < m.F.rows(); ++f) v += m.V.row(m.F(f, 0)).cross(m.V.row(m.F(f, 1))).dot(m.V.row(m.F(f, 2))) / 6.0;
  return v;
}

// Every directed edge appears once and its opposite exists: closed and consistently oriented.
bool closed_and_oriented(const Mesh& m) {
  std::set<std::pair<int, int>> directed;
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (!directed.insert({m.F(f, k), m.F(f, (k + 1) % 3)}).second) return false;
  for (const auto& [a, b] : directed)
    if (!directed.count({b, a})) return false;
  return true;
}

TEST(Shapes, BoxIsClosedOutwardWithExactVolume) {
  Mesh box = make_box(2, 3, 4, 3);
  EXPECT_TRUE(closed_and_oriented(box));
  EXPECT_NEAR(enclosed_volume(box), 24.0, 1e-12);
  EXPECT_EQ(box.V.rows(), 6 * 9 + 2);  // V - E + F = 2 with 6 * 3^2 quads
}

TEST(Shapes, BarCageSpansTheRequestedBox) {
  Mesh cage = make_bar_cage(-1.5, 1.5, 0.6, 0.4, 4);
  EXPECT_TRUE(closed_and_oriented(cage));
  EXPECT_NEAR(enclosed_volume(cage), 3.0 * 1.2 * 0.8, 1e-12);
  EXPECT_EQ(cage.V.rows(), 5 * 4);
}

TEST(Shapes, IcosphereApproachesTheBallVolume) {
  Mesh sphere = make_icosphere(4, 2.0);
  EXPECT_TRUE(closed_and_oriented(sphere));
  EXPECT_EQ(sphere.V.rows(), 10 * 256 + 2);
  EXPECT_NEAR(enclosed_volume(sphere), 4.0 / 3.0 * M_PI * 8.0, 0.02 * 4.0 / 3.0 * M_PI * 8.0);
  EXPECT_GT(enclosed_volume(sphere), 0.0);
}

TEST(Shapes, CapsuleIsClosedOutwardAndNearItsAnalyticVolume) {
  Mesh capsule = make_capsule(2.0, 0.5, 12, 16, 48);
  EXPECT_TRUE(closed_and_oriented(capsule));
  const double exact = M_PI * 0.25 * 2.0 + 4.0 / 3.0 * M_PI * 0.125;
  EXPECT_NEAR(enclosed_volume(capsule), exact, 0.01 * exact);
}

TEST(Shapes, TorusIsClosedOutwardGenusOneNearItsAnalyticVolume) {
  Mesh torus = make_torus(1.0, 0.3, 48, 24);
  EXPECT_TRUE(closed_and_oriented(torus));
  const double exact = 2 * M_PI * M_PI * 1.0 * 0.09;
  EXPECT_NEAR(enclosed_volume(torus), exact, 0.02 * exact);
  const int edges = static_cast<int>(torus.F.rows()) * 3 / 2;
  EXPECT_EQ(torus.V.rows() - edges + torus.F.rows(), 0) << "Euler characteristic of a torus";
}

// The bend keeps lengths along y = 0 (the bar's axis becomes an arc of the same length), keeps the
// orientation (a closed outward mesh stays outward) and, for a thin bar, nearly its volume.
TEST(Shapes, BendAlongXKeepsTheAxisLengthAndTheOrientation) {
  const double radius = 1.5;
  Vertices axis(3, 3);
  axis << -2.0, 0, 0, 0, 0, 0, 2.0, 0, 0;
  const Vertices arc = bend_along_x(axis, radius);
  EXPECT_LE(arc.row(1).norm(), 1e-15);                                                 // x = 0 stays put
  EXPECT_NEAR((arc.row(2) - Eigen::RowVector3d(0, radius, 0)).norm(), radius, 1e-12);  // on the circle
  EXPECT_NEAR(std::atan2(arc(2, 0), radius - arc(2, 1)), 2.0 / radius, 1e-12);         // at angle length / radius
  Mesh bar = make_capsule(4.0, 0.2, 6, 24, 16);
  const double straight = enclosed_volume(bar);
  bar.V = bend_along_x(bar.V, radius);
  EXPECT_TRUE(closed_and_oriented(bar));
  EXPECT_NEAR(enclosed_volume(bar), straight, 0.02 * straight);
}

}  // namespace
}  // namespace sd
