#include "core/mesh/topology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "core/mesh/shapes.h"
#include "core/parts/partition.h"
#include "test_support.h"

namespace sd {
namespace {

Faces faces_of(const std::vector<Eigen::RowVector3i>& rows) {
  Faces F(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) F.row(static_cast<Eigen::Index>(i)) = rows[i];
  return F;
}

// The outward tetrahedron on vertices o .. o + 3.
std::vector<Eigen::RowVector3i> tetra_faces(int o) {
  return {{o, o + 2, o + 1}, {o, o + 1, o + 3}, {o, o + 3, o + 2}, {o + 1, o + 2, o + 3}};
}

const Edge* find_edge(const EdgeUses& uses, int a, int b) {
  for (const Edge& e : uses.edges())
    if (e.lo == std::min(a, b) && e.hi == std::max(a, b)) return &e;
  return nullptr;
}

TEST(DisjointSets, TheRootOfASetIsItsSmallestElement) {
  DisjointSets sets(8);
  sets.unite(5, 7);
  sets.unite(7, 3);
  sets.unite(6, 1);
  sets.unite(3, 6);  // {1, 3, 5, 6, 7}
  for (int v : {1, 3, 5, 6, 7}) EXPECT_EQ(sets.find(v), 1) << v;
  for (int v : {0, 2, 4}) EXPECT_EQ(sets.find(v), v) << v;
  sets.unite(6, 6);
  sets.unite(7, 5);  // already one set: nothing changes
  EXPECT_EQ(sets.find(7), 1);
  EXPECT_EQ(sets.size(), 8);
}

TEST(EdgeUses, AClosedSphereHasEachEdgeTwiceInOppositeDirections) {
  const Mesh sphere = make_icosphere(2);
  const EdgeUses uses(sphere.F);
  const auto F = static_cast<int>(sphere.F.rows()), V = static_cast<int>(sphere.V.rows());
  ASSERT_EQ(uses.uses().size(), 3u * F);
  EXPECT_EQ(static_cast<int>(uses.edges().size()) * 2, 3 * F);
  EXPECT_EQ(V - static_cast<int>(uses.edges().size()) + F, 2);  // Euler: a sphere
  for (const Edge& e : uses.edges()) {
    EXPECT_EQ(e.faces, 2);
    EXPECT_EQ(e.forward, 1);
    EXPECT_FALSE(e.boundary() || e.non_manifold() || e.misoriented());
  }
  EXPECT_EQ(boundary_loop_count(uses), 0);
}

TEST(EdgeUses, AreSortedByEdgeAndEachUseNamesAFaceOnItsEdge) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> vertex(0, 9);
  std::vector<Eigen::RowVector3i> rows;
  while (rows.size() < 40) {
    const Eigen::RowVector3i t(vertex(rng), vertex(rng), vertex(rng));
    if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) rows.push_back(t);
  }
  const Faces F = faces_of(rows);
  const EdgeUses uses(F);
  int total = 0;
  for (size_t i = 0; i < uses.edges().size(); ++i) {
    const Edge& e = uses.edges()[i];
    ASSERT_LT(e.lo, e.hi);
    if (i > 0) {
      EXPECT_LT(std::make_pair(uses.edges()[i - 1].lo, uses.edges()[i - 1].hi), std::make_pair(e.lo, e.hi));
    }
    EXPECT_EQ(e.first, total);
    int forward = 0;
    for (int k = 0; k < e.faces; ++k) {
      const EdgeUse& u = uses.uses_of(e)[k];
      EXPECT_EQ(u.lo, e.lo);
      EXPECT_EQ(u.hi, e.hi);
      // The face walks lo -> hi exactly when one of its corners is followed by the next.
      bool walks_forward = false, has_edge = false;
      for (int c = 0; c < 3; ++c) {
        const int a = F(u.face, c), b = F(u.face, (c + 1) % 3);
        has_edge |= std::min(a, b) == e.lo && std::max(a, b) == e.hi;
        walks_forward |= a == e.lo && b == e.hi;
      }
      EXPECT_TRUE(has_edge);
      EXPECT_EQ(u.forward, walks_forward);
      forward += u.forward;
    }
    EXPECT_EQ(e.forward, forward);
    total += e.faces;
  }
  EXPECT_EQ(total, 3 * 40);
}

TEST(EdgeUses, NameEveryFaceOfANonManifoldEdge) {
  // Three triangles on edge 0-1 (a book of three pages), the third walking it 0 -> 1.
  const Faces F = faces_of({{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const EdgeUses uses(F);
  const Edge* spine = find_edge(uses, 0, 1);
  ASSERT_NE(spine, nullptr);
  EXPECT_EQ(spine->faces, 3);
  EXPECT_EQ(spine->forward, 2);
  EXPECT_TRUE(spine->non_manifold());
  std::vector<int> faces;
  for (int k = 0; k < spine->faces; ++k) faces.push_back(uses.uses_of(*spine)[k].face);
  std::sort(faces.begin(), faces.end());
  EXPECT_EQ(faces, (std::vector<int>{0, 1, 2}));
  // The six outer edges each have one face: three pages, one boundary piece (they meet at the spine's ends).
  int boundary = 0;
  for (const Edge& e : uses.edges()) boundary += e.boundary();
  EXPECT_EQ(boundary, 6);
  EXPECT_EQ(boundary_loop_count(uses), 1);
}

TEST(EdgeUses, AnEdgeWalkedTheSameWayByBothFacesIsMisoriented) {
  const EdgeUses consistent(faces_of({{0, 1, 2}, {1, 0, 3}}));
  EXPECT_FALSE(find_edge(consistent, 0, 1)->misoriented());
  const EdgeUses flipped(faces_of({{0, 1, 2}, {0, 1, 3}}));
  EXPECT_TRUE(find_edge(flipped, 0, 1)->misoriented());
  EXPECT_EQ(find_edge(flipped, 0, 1)->forward, 2);
}

TEST(EdgeUses, TakeOnlyTheListedFaces) {
  const Faces F = faces_of(tetra_faces(0));
  const EdgeUses two(F, {1, 3});
  EXPECT_EQ(two.uses().size(), 6u);
  for (const EdgeUse& u : two.uses()) EXPECT_TRUE(u.face == 1 || u.face == 3);
  EXPECT_EQ(find_edge(two, 1, 3)->faces, 2);  // the edge the two faces share
  EXPECT_EQ(two.edges().size(), 5u);
}

TEST(BoundaryLoops, AnOpenSphereHasOneLoopPerHole) {
  const Mesh sphere = make_icosphere(3);
  // Caps cut off at both poles and a window in the side: three holes.
  const Mesh open = test::drop_faces(sphere, [](const Eigen::RowVector3d& c) {
    return c.z() > 0.8 || c.z() < -0.8 || (c.x() > 0.9 && std::abs(c.z()) < 0.2);
  });
  const EdgeUses uses(open.F);
  EXPECT_EQ(boundary_loop_count(uses), 3);
  // Every boundary vertex lies on exactly two boundary edges (simple loops).
  std::vector<int> degree(static_cast<size_t>(open.V.rows()), 0);
  for (const Edge& e : uses.edges())
    if (e.boundary()) ++degree[e.lo], ++degree[e.hi];
  for (int d : degree) EXPECT_TRUE(d == 0 || d == 2) << d;
}

TEST(BoundaryLoops, TwoHolesMeetingAtAVertexAreOnePiece) {
  // Two triangles touching at vertex 0: a figure eight of boundary edges.
  const EdgeUses uses(faces_of({{0, 1, 2}, {0, 3, 4}}));
  EXPECT_EQ(boundary_loop_count(uses), 1);
  EXPECT_EQ(boundary_loop_count(EdgeUses(faces_of({{0, 1, 2}, {3, 4, 5}}))), 2);
}

TEST(Components, TwoSpheresAreTwoComponentsNumberedByTheirFirstFace) {
  const Mesh a = make_icosphere(1), b = make_icosphere(2);
  const Mesh both = test::join_meshes(a, b);
  const Components c = connected_components(both.F);
  EXPECT_EQ(c.count, 2);
  ASSERT_EQ(c.of_face.size(), static_cast<size_t>(both.F.rows()));
  for (Eigen::Index f = 0; f < both.F.rows(); ++f) EXPECT_EQ(c.of_face[f], f < a.F.rows() ? 0 : 1) << f;
  // The second sphere's faces first: it is component 0, whatever its vertex numbers.
  Faces swapped(both.F.rows(), 3);
  swapped << both.F.bottomRows(b.F.rows()), both.F.topRows(a.F.rows());
  const Components d = connected_components(swapped);
  EXPECT_EQ(d.count, 2);
  EXPECT_EQ(d.of_face.front(), 0);
  EXPECT_EQ(d.of_face.back(), 1);
  EXPECT_EQ(component_parts(swapped), d.of_face);  // the parts' components are these
}

TEST(Components, JoinThroughASharedVertexAndSkipFacesNotListed) {
  // Two tetrahedra sharing vertex 3 (0..3 and 3..6), and a third apart (7..10).
  std::vector<Eigen::RowVector3i> rows = tetra_faces(0);
  for (const auto& t : tetra_faces(3)) rows.push_back(t);
  for (const auto& t : tetra_faces(7)) rows.push_back(t);
  const Faces F = faces_of(rows);
  EXPECT_EQ(connected_components(F).count, 2);
  // Without the first tetrahedron's faces on vertex 3, its one face left (0 2 1) stands alone.
  const Components c = connected_components(F, 11, {0, 4, 5, 6, 7, 8, 9, 10, 11});
  EXPECT_EQ(c.count, 3);
  for (int f : {1, 2, 3}) EXPECT_EQ(c.of_face[f], -1) << f;
  EXPECT_EQ(c.of_face[0], 0);
  EXPECT_EQ(c.of_face[4], 1);
  EXPECT_EQ(c.of_face[11], 2);
  // Face 1 2 3 touches the second tetrahedron at vertex 3 only: one component with it.
  EXPECT_EQ(connected_components(F, 11, {3, 4}).count, 1);
  EXPECT_EQ(connected_components(Faces(0, 3)).count, 0);
}

TEST(NonManifoldVertices, TheTipTwoConesShare) {
  std::vector<Eigen::RowVector3i> rows = tetra_faces(0);
  for (const auto& t : tetra_faces(3)) rows.push_back(t);
  const Faces F = faces_of(rows);
  EXPECT_EQ(non_manifold_vertices(F, 7, all_faces(F)), std::vector<int>{3});
  const Mesh sphere = make_icosphere(2);
  EXPECT_TRUE(non_manifold_vertices(sphere.F, static_cast<int>(sphere.V.rows()), all_faces(sphere.F)).empty());
  // An open fan (a vertex on the boundary) is one fan, not several.
  const Faces fan = faces_of({{0, 1, 2}, {0, 2, 3}, {0, 3, 4}});
  EXPECT_TRUE(non_manifold_vertices(fan, 5, all_faces(fan)).empty());
}

TEST(DuplicateFaces, SameThreeVerticesInEitherOrientation) {
  // Faces 0, 2 and 4 are one triangle (4 flipped); 1 and 3 share only an edge.
  const Faces F = faces_of({{0, 1, 2}, {1, 2, 3}, {1, 2, 0}, {2, 1, 4}, {0, 2, 1}});
  EXPECT_EQ(duplicate_faces(F, all_faces(F)), (std::vector<std::pair<int, int>>{{0, 2}, {2, 4}}));
  EXPECT_EQ(duplicate_faces(F, {0, 1, 3, 4}), (std::vector<std::pair<int, int>>{{0, 4}}));
  const Mesh sphere = make_icosphere(2);
  EXPECT_TRUE(duplicate_faces(sphere.F, all_faces(sphere.F)).empty());
}

}  // namespace
}  // namespace sd
