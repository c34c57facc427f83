// The file layout -> solver topology map: welding split vertices, dropping and carrying unreferenced ones,
// splitting non-manifold vertices and edges, and mapping handles, targets and parts given in file numbering.
#include "core/mesh/mesh_layout.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <vector>

#include "core/error.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/shapes.h"
#include "core/mesh/volume.h"
#include "test_support.h"

namespace sd {
namespace {

// Every face with its own three vertices (non-indexed geometry, or a flat-shaded export).
Mesh split_per_face(const Mesh& m) {
  Mesh out;
  out.V.resize(3 * m.F.rows(), 3);
  out.F.resize(m.F.rows(), 3);
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      out.V.row(3 * f + k) = m.V.row(m.F(f, k));
      out.F(f, k) = 3 * f + k;
    }
  return out;
}

Mesh tetra() {
  Mesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return m;
}

const Finding* find(const CheckReport& r, const std::string& code) {
  for (const Finding& f : r.findings)
    if (f.code == code) return &f;
  return nullptr;
}

TEST(MeshLayout, CleanMeshIsTheIdentity) {
  const Mesh m = make_icosphere(2, 1.0);
  const MeshLayout layout(m);
  EXPECT_TRUE(layout.identity());
  EXPECT_EQ(layout.mesh().V, m.V);
  EXPECT_EQ(layout.mesh().F, m.F);
  EXPECT_EQ(layout.to_file(m.V * 2.0), m.V * 2.0);
  const CheckReport r = check_model(layout);
  EXPECT_TRUE(r.findings.empty()) << r.text();
}

// A closed box whose faces each have their own vertices welds back to the closed box; positions return to
// every corner copy.
TEST(MeshLayout, WeldsSplitVerticesBackIntoTheClosedSurface) {
  const Mesh box = make_box(2, 3, 4, 2);
  const Mesh split = split_per_face(box);
  const MeshLayout layout(split);
  EXPECT_FALSE(layout.identity());
  EXPECT_EQ(layout.mesh().V.rows(), box.V.rows());
  EXPECT_EQ(layout.mesh().F.rows(), box.F.rows());
  EXPECT_EQ(layout.stats().welded, split.V.rows() - box.V.rows());
  EXPECT_DOUBLE_EQ(signed_volume(layout.mesh().V, layout.mesh().F), 24.0);
  const CheckReport r = check_model(layout);
  EXPECT_TRUE(r.ok()) << r.text();
  ASSERT_NE(find(r, "welded"), nullptr);
  EXPECT_EQ(find(r, "welded")->severity, Severity::Note);
  EXPECT_EQ(find(r, "open"), nullptr);
  EXPECT_EQ(r.summary.vertices, split.V.rows());
  EXPECT_EQ(r.summary.components, 1);
  EXPECT_EQ(r.summary.genus, 0);
  // The same file checked vertex by vertex is open with one component per face.
  const CheckReport raw = check_mesh(split);
  EXPECT_FALSE(raw.ok());
  EXPECT_EQ(raw.summary.components, box.F.rows());
  const Vertices moved = (layout.mesh().V * 1.5).rowwise() + Eigen::RowVector3d(1, 2, 3);
  const Vertices file = layout.to_file(moved);
  for (int f = 0; f < split.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(file.row(3 * f + k), moved.row(layout.solver_vertices(3 * f + k)[0]));
}

TEST(MeshLayout, WeldsWithinTheToleranceOnly) {
  Mesh split = split_per_face(make_icosphere(1, 1.0));
  const double diagonal = bounding_box_diagonal(split.V);
  split.V(4, 0) += 0.3e-6 * diagonal;  // within 1e-6 of the diagonal: still the same point
  EXPECT_EQ(MeshLayout(split).mesh().V.rows(), 42);
  split.V(4, 0) += 10e-6 * diagonal;  // beyond: its own point, and the surface opens there
  EXPECT_EQ(MeshLayout(split).mesh().V.rows(), 43);
  LayoutOptions exact;
  exact.weld_tolerance = 0;
  split.V(4, 0) = split.V(1, 0) + 1e-15;
  EXPECT_GT(MeshLayout(split, exact).mesh().V.rows(), 42);
  EXPECT_THROW(MeshLayout(split, LayoutOptions{0.5}), Error);
}

// Issue: a tetrahedron plus one vertex no face uses. The solver leaves the vertex out; it follows the nearest
// face rigidly, so a rigid motion of the mesh moves it rigidly too.
TEST(MeshLayout, UnreferencedVertexIsCarriedAlongRigidly) {
  Mesh m = tetra();
  m.V.conservativeResize(5, 3);
  m.V.row(4) << 0.7, 0.6, 0.9;
  const MeshLayout layout(m);
  EXPECT_EQ(layout.mesh().V.rows(), 4);
  EXPECT_EQ(layout.stats().unreferenced, 1);
  EXPECT_TRUE(layout.solver_vertices(4).empty());
  EXPECT_EQ(layout.solver_of_file()[4], -1);
  EXPECT_LE((layout.to_file(layout.mesh().V).row(4) - m.V.row(4)).norm(), 1e-15);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::RowVector3d t(3, -1, 2);
  const Vertices moved = (layout.mesh().V * R.transpose()).rowwise() + t;
  const Eigen::RowVector3d expected = m.V.row(4) * R.transpose() + t;
  EXPECT_LE((layout.to_file(moved).row(4) - expected).norm(), 1e-12);
  const CheckReport r = check_model(layout);
  EXPECT_TRUE(r.ok()) << r.text();
  ASSERT_NE(find(r, "unreferenced_vertices"), nullptr);
  EXPECT_NE(find(r, "unreferenced_vertices")->message.find("(first: 4); they are carried along"), std::string::npos);
  test::expect_error([&] { layout.map_handles({{0, 4}}); }, "vertex 4, which no triangle uses");
}

// The weld tolerance follows the surface, not a vertex no face uses: a stray one at 1e5 (an exporter's leftover)
// had made the tolerance 0.1 and welded the whole tetrahedron into a point ("the mesh has no faces").
TEST(MeshLayout, AFarUnreferencedVertexLeavesTheSurfaceAsItIs) {
  Mesh m = tetra();
  m.V.conservativeResize(5, 3);
  m.V.row(4) << 1e5, 0, 0;
  const MeshLayout layout(m);
  EXPECT_EQ(layout.mesh().F.rows(), 4);
  EXPECT_EQ(layout.stats().welded, 0);
  EXPECT_EQ(layout.stats().unreferenced, 1);
  const CheckReport r = check_model(layout);
  EXPECT_TRUE(r.ok()) << r.text();
}

// Per-vertex values (a column of W for the influence view) go to the file's numbering as positions do: every
// copy of a welded point takes its value, a carried vertex the value at its closest point.
TEST(MeshLayout, ValuesGoToTheFileLayoutLikePositions) {
  const Mesh split = split_per_face(make_box(2, 3, 4, 2));
  const MeshLayout welded(split);
  const Eigen::VectorXd x = welded.mesh().V.col(0);  // a linear function: x
  const Eigen::VectorXd file = welded.values_to_file(x);
  ASSERT_EQ(file.size(), split.V.rows());
  for (int v = 0; v < split.V.rows(); ++v) EXPECT_DOUBLE_EQ(file[v], split.V(v, 0));
  Mesh m = tetra();
  m.V.conservativeResize(5, 3);
  m.V.row(4) << 0.7, 0.6, 0.9;  // carried: follows face (1, 2, 3), its closest point there
  const MeshLayout carried(m);
  const Eigen::VectorXd sum = carried.mesh().V.rowwise().sum();  // x + y + z, linear: 1 on that face
  EXPECT_NEAR(carried.values_to_file(sum)[4], 1.0, 1e-15);
  EXPECT_THROW(carried.values_to_file(Eigen::VectorXd::Zero(5)), Error);
}

// Two tetrahedra touching at a corner (a non-manifold vertex), and two boxes sharing an edge (four faces around
// it): split into manifold surfaces, one vertex again in the file.
TEST(MeshLayout, SplitsNonManifoldVerticesAndPairsFacesAroundEdges) {
  Mesh second = tetra();
  second.V = -second.V;  // mirrored through the shared corner at the origin...
  for (int f = 0; f < second.F.rows(); ++f) std::swap(second.F(f, 1), second.F(f, 2));  // ... and outward again
  const Mesh bowtie = split_per_face(test::join_meshes(tetra(), second));
  const MeshLayout touching(bowtie);
  EXPECT_EQ(touching.stats().split_vertices, 1);
  EXPECT_EQ(touching.mesh().V.rows(), 8);
  const CheckReport r = check_model(touching);
  EXPECT_TRUE(r.ok()) << r.text();
  EXPECT_NE(find(r, "split_vertices"), nullptr);
  EXPECT_EQ(r.summary.components, 2);

  Mesh a = make_box(1, 1, 1, 1), b = make_box(1, 1, 1, 1);
  a.V.rowwise() += Eigen::RowVector3d(0.5, 0.5, 0);
  b.V.rowwise() += Eigen::RowVector3d(-0.5, -0.5, 0);  // the boxes share the edge x = y = 0
  const MeshLayout boxes(split_per_face(test::join_meshes(a, b)));
  EXPECT_EQ(boxes.stats().paired_edges, 1);
  EXPECT_EQ(boxes.stats().split_vertices, 2);
  const CheckReport both = check_model(boxes);
  EXPECT_TRUE(both.ok()) << both.text();
  EXPECT_EQ(both.summary.components, 2);
  EXPECT_NEAR(both.summary.volume, 2.0, 1e-12);
}

// Three faces on one edge (a fin on a surface) cannot be paired: the check names the edge in file numbers.
TEST(MeshLayout, UnpairableEdgeIsNamedInFileNumbers) {
  Mesh m = tetra();
  m.V.conservativeResize(6, 3);
  m.V.row(4) << 1, 1, 0;  // a fin on edge 1-2, given twice (a split vertex) ...
  m.V.row(5) << 1, 1, 0;
  m.F.conservativeResize(5, 3);
  m.F.row(4) << 1, 5, 2;
  const MeshLayout layout(m);
  EXPECT_EQ(layout.stats().paired_edges, 0);
  const CheckReport r = check_model(layout);
  EXPECT_FALSE(r.ok());
  ASSERT_NE(find(r, "non_manifold_edge"), nullptr) << r.text();
  EXPECT_NE(find(r, "non_manifold_edge")->message.find("first: 1-2"), std::string::npos) << r.text();
  EXPECT_EQ(layout.solver_vertices(4), layout.solver_vertices(5));  // ... welded into one point
}

TEST(MeshLayout, FacesWhoseCornersWeldTogetherAreDropped) {
  Mesh m = split_per_face(make_icosphere(1, 1.0));
  const int faces = static_cast<int>(m.F.rows());
  m.V.conservativeResize(m.V.rows() + 3, 3);
  m.V.bottomRows(3) << 1, 0, 0, 1, 0, 0, 1, 1e-9, 0;  // a sliver: its corners are one point within tolerance
  m.F.conservativeResize(faces + 1, 3);
  m.F.row(faces) << static_cast<int>(m.V.rows()) - 3, static_cast<int>(m.V.rows()) - 2,
      static_cast<int>(m.V.rows()) - 1;
  const MeshLayout layout(m);
  EXPECT_EQ(layout.stats().collapsed_faces, 1);
  EXPECT_EQ(layout.mesh().F.rows(), faces);
  EXPECT_EQ(layout.solver_face(faces), -1);
  const CheckReport r = check_model(layout);
  EXPECT_TRUE(r.ok()) << r.text();
  EXPECT_NE(find(r, "collapsed_faces"), nullptr);
  // Parts given per file face map to the solver's faces and back (the collapsed face takes a neighbour's).
  std::vector<int> parts(static_cast<size_t>(faces + 1));
  for (int f = 0; f <= faces; ++f) parts[f] = m.V(m.F(f, 0), 0) > 0 ? 1 : 0;
  const std::vector<int> solver_parts = layout.solver_face_parts(parts);
  ASSERT_EQ(solver_parts.size(), static_cast<size_t>(faces));
  for (int s = 0; s < faces; ++s) EXPECT_EQ(solver_parts[s], parts[layout.file_face(s)]);
  const std::vector<int> back = layout.file_face_parts(solver_parts);
  for (int f = 0; f < faces; ++f) EXPECT_EQ(back[f], parts[f]);
  EXPECT_EQ(back[faces], 1);
}

TEST(MeshLayout, HandlesInFileNumbersMapToSolverVertices) {
  const Mesh box = make_box(1, 1, 1, 1);
  const Mesh split = split_per_face(box);
  const MeshLayout layout(split);
  // File vertices 0 and 3 * f + k at the same corner: one solver vertex, given once.
  int twin = -1;
  for (int v = 1; v < split.V.rows(); ++v)
    if (split.V.row(v) == split.V.row(0)) twin = v;
  ASSERT_GT(twin, 0);
  const HandleMap map = layout.map_handles({{0, twin, 1}, {5}});
  ASSERT_EQ(map.groups.size(), 2u);
  EXPECT_EQ(map.groups[0].size(), layout.solver_vertices(0) == layout.solver_vertices(1) ? 1u : 2u);
  EXPECT_EQ(map.file_rows, 4);
  Vertices file_targets(4, 3);
  file_targets << 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3;
  const Vertices targets = layout.solver_targets(map, file_targets);
  EXPECT_EQ(targets.row(0), file_targets.row(0));
  EXPECT_EQ(targets.bottomRows(1), file_targets.bottomRows(1));
  test::expect_error([&] { layout.map_handles({{0}, {twin}}); }, "(one point: welded) in both group 0 and group 1");
  test::expect_error([&] { layout.map_handles({{0, 0}}); }, "appears twice in group 0");
  test::expect_error([&] { layout.map_handles({{static_cast<int>(split.V.rows())}}); }, "outside [0, ");
  test::expect_error([&] { layout.solver_targets(map, Vertices(3, 3)); }, "for 4 handle vertices");
}

TEST(MeshLayout, BadInputKeepsTheIdentityForTheCheckToName) {
  Mesh m = tetra();
  m.F(0, 0) = 9;
  const MeshLayout layout(m);
  EXPECT_TRUE(layout.identity());
  const CheckReport r = check_model(layout);
  ASSERT_NE(find(r, "index_out_of_range"), nullptr) << r.text();
  Mesh huge = tetra();
  huge.V *= 1e300;  // the diagonal overflows: no tolerance to weld with
  EXPECT_TRUE(MeshLayout(huge).identity());
  ASSERT_NE(find(check_model(huge), "coordinates_too_large"), nullptr);
  // One corner beyond 1e30 but the diagonal finite: the check names it (it had welded the rest into a point).
  Mesh one_huge = tetra();
  one_huge.V(3, 2) = 3e38;
  EXPECT_TRUE(MeshLayout(one_huge).identity());
  ASSERT_NE(find(check_model(MeshLayout(one_huge)), "coordinates_too_large"), nullptr);
  // Every face collapses into one point, and a vertex no face uses has nothing to follow: no crash, it stays.
  Mesh point = tetra();
  point.V.topRows(4).setZero();
  point.V.conservativeResize(5, 3);
  point.V.row(4) << 1, 2, 3;
  const MeshLayout empty(point);
  EXPECT_EQ(empty.mesh().F.rows(), 0);
  EXPECT_EQ(empty.to_file(empty.mesh().V).row(4), point.V.row(4));
  EXPECT_FALSE(check_model(empty).ok());
}

}  // namespace
}  // namespace sd
