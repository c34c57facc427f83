#include "core/basis/internal/cage_grid.h"

#include <gtest/gtest.h>

#include "core/geometry/winding_number.h"
#include "core/mesh/shapes.h"
#include "basis/cage_fixtures.h"

namespace sd {
namespace {

// Inside by crossing parity agrees with the winding number, away from the cage (where either may round).
void expect_inside_agrees_with_winding_number(const Mesh& cage, double spacing) {
  const CageGrid grid(cage, spacing);
  const Eigen::Array3i n = grid.counts();
  int inside = 0, checked = 0;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const double w = winding_number(cage, grid.position(i, j, k).transpose());
        if (std::abs(w - 0.5) < 0.05) continue;
        ++checked;
        EXPECT_EQ(grid.inside(grid.node(i, j, k)), w > 0.5) << i << " " << j << " " << k;
        inside += w > 0.5;
      }
  EXPECT_GT(inside, 10);
  EXPECT_GT(checked, inside);
}

TEST(CageGrid, InsideNodesAgreeWithTheWindingNumber) {
  expect_inside_agrees_with_winding_number(test::star_cage(), 0.1);
  expect_inside_agrees_with_winding_number(test::l_prism(), 0.13);
  expect_inside_agrees_with_winding_number(test::bent_bar().cage, 0.15);
  // An axis-aligned box whose faces lie at round coordinates, with a round spacing: nodes are shifted off them.
  expect_inside_agrees_with_winding_number(make_box(2, 2, 2, 3), 0.25);
}

// Along a line, the crossings with a closed cage come in pairs, and each one's barycentric coordinates put it
// on its triangle at the line's coordinate.
TEST(CageGrid, CrossingsLieOnTheirTrianglesInPairs) {
  const Mesh cage = test::bent_bar().cage;
  const CageGrid grid(cage, 0.11);
  const Eigen::Array3i n = grid.counts();
  std::vector<const GridCrossing*> crossings;
  long long total = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const int index[3] = {i, j, k};
          if (index[axis] != 0) continue;  // one walk per line: from its first node to past its last
          int count = 0;
          for (int step = 0; step + 1 < n[axis]; ++step) {
            int at[3] = {i, j, k};
            at[axis] = step;
            grid.crossings_between(axis, at[0], at[1], at[2], 1, crossings);
            for (const GridCrossing* c : crossings) {
              ++count;
              Eigen::Vector3d point = Eigen::Vector3d::Zero();
              for (int v = 0; v < 3; ++v) point += c->bary[v] * cage.V.row(cage.F(c->face, v)).transpose();
              Eigen::Vector3d expected = grid.position(at[0], at[1], at[2]);
              expected[axis] = c->at;
              EXPECT_LE((point - expected).norm(), 1e-12);
            }
          }
          EXPECT_EQ(count % 2, 0);
          total += count;
        }
  EXPECT_EQ(total, grid.crossing_count());
  EXPECT_GT(total, 100);
}

}  // namespace
}  // namespace sd
