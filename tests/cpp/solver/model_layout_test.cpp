// The Deformer on the meshes people have: open meshes keep their capped volume, separate components each keep
// their own, split (seam) vertices deform like the welded mesh, and a vertex no face uses is carried along --
// with every method.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "core/mesh/mesh_check.h"
#include "core/mesh/shapes.h"
#include "core/solver/deformer.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "solver_fixtures.h"
#include "test_support.h"

namespace sd {
namespace {

using test::Combo;
using test::kCombos;
using test::open_capsule_scene;
using test::Scene;

SolverOptions options_for(Method method, JacobianMode mode = JacobianMode::Fast) {
  SolverOptions o;
  o.method = method;
  o.jacobian = mode;
  o.max_iterations = 200;
  return o;
}

double diagonal(const Mesh& m) { return bounding_box_diagonal(m.V); }

// Largest relative change of the part volumes (the default parts: components, or the capped whole).
double worst_part_change(const Deformer& d) {
  const Eigen::VectorXd rest = d.rest_part_volumes(), now = d.part_volumes();
  return ((now - rest).array() / rest.array().abs()).abs().maxCoeff();
}

TEST(OpenMesh, IsAcceptedWithANoteAndKeepsItsCappedVolume) {
  const Scene s = open_capsule_scene();
  const CheckReport report = check_model(s.mesh);
  ASSERT_TRUE(report.ok()) << report.text();
  EXPECT_EQ(report.summary.holes, 1);
  for (const Combo& c : kCombos) {
    Deformer d(s.mesh, s.cage);
    EXPECT_EQ(d.rest_part_volumes().size(), 1);
    d.set_options(options_for(c.method, c.mode));
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    const StepResult r = d.solve();
    EXPECT_TRUE(d.positions().allFinite()) << c.name;
    EXPECT_LE(worst_part_change(d), 1e-6) << c.name << ": " << r.stop_reason;
    const int right = s.groups[1][0];
    EXPECT_GT((d.positions().row(right) - s.mesh.V.row(right)).norm(), 0.3) << c.name;
    std::cout << "[          ] " << c.name << ": capped volume change " << worst_part_change(d) << " after "
              << r.iterations.size() << " iterations\n";
  }
}

// The boundary rows (laplacian_coordinates.h) keep the rest pose a fixed point: with the targets at rest
// nothing moves, with any method.
TEST(OpenMesh, RestPoseStaysPut) {
  Scene s = open_capsule_scene();
  s.targets.setZero();
  int r = 0;
  for (const auto& g : s.groups)
    for (int v : g) s.targets.row(r++) = s.mesh.V.row(v);
  for (const Combo& c : kCombos) {
    Deformer d(s.mesh, s.cage);
    d.set_options(options_for(c.method, c.mode));
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    d.step(3);
    EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.positions() - s.mesh.V)), 1e-10 * diagonal(s.mesh)) << c.name;
  }
}

TEST(OpenMesh, ArapAndTheSpectralBasisRunToo) {
  const Scene s = open_capsule_scene();
  Deformer arap(s.mesh, s.cage);
  arap.set_options(options_for(Method::Arap));
  arap.set_handles(s.groups);
  arap.set_targets(s.targets);
  arap.solve();
  EXPECT_TRUE(arap.positions().allFinite());
  BasisOptions spectral;
  spectral.kind = BasisKind::Spectral;
  spectral.spectral.modes = 20;
  Deformer d(s.mesh, Mesh{}, spectral);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  d.solve();
  EXPECT_TRUE(d.positions().allFinite());
  EXPECT_LE(worst_part_change(d), 1e-6);
}

// The scene solved by the subspace method with reduced integration.
StepResult solve_reduced(Deformer& d, const Scene& s, JacobianMode mode) {
  SolverOptions o = options_for(Method::Subspace, mode);
  o.integration = Integration::Reduced;
  d.set_options(o);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  return d.solve();
}

// Reduced integration samples the Laplacian rows, the boundary ones of an open mesh among them: the capped
// volume and the two components' volumes are kept as with the full sum.
TEST(OpenMesh, ReducedIntegrationKeepsTheCappedVolume) {
  const Scene s = open_capsule_scene();
  for (JacobianMode mode : {JacobianMode::Fast, JacobianMode::Exact}) {
    Deformer d(s.mesh, s.cage);
    const StepResult r = solve_reduced(d, s, mode);
    ASSERT_FALSE(r.iterations.empty());
    EXPECT_GT(r.iterations.front().samples, 0);  // the rule's iterations first (then finishing ones on every vertex)
    EXPECT_TRUE(d.positions().allFinite());
    EXPECT_LE(worst_part_change(d), 1e-6) << r.stop_reason;
    const int right = s.groups[1][0];
    EXPECT_GT((d.positions().row(right) - s.mesh.V.row(right)).norm(), 0.3);
  }
}

// Two separate spheres in one cage, the left end and the right sphere's middle fixed, the right end pulled.
Scene two_spheres_scene() {
  Mesh a = make_icosphere(3, 0.45), b = make_icosphere(3, 0.45);
  a.V.col(0).array() -= 0.8;
  b.V.col(0).array() += 0.8;
  Scene s;
  s.mesh = test::join_meshes(a, b);
  s.cage = make_bar_cage(-1.6, 1.6, 0.7, 0.7, 4);
  s.groups = {test::vertices_where(
                  s.mesh, [](const Eigen::RowVector3d& p) { return p.x() < -1.1 || std::abs(p.x() - 0.8) < 0.1; }),
              test::vertices_where(s.mesh, [](const Eigen::RowVector3d& p) { return p.x() > 1.15; })};
  s.targets.resize(static_cast<Eigen::Index>(s.groups[0].size() + s.groups[1].size()), 3);
  int r = 0;
  for (size_t g = 0; g < 2; ++g)
    for (int v : s.groups[g])
      s.targets.row(r++) = s.mesh.V.row(v) + (g == 1 ? Eigen::RowVector3d(0.35, 0.1, 0) : Eigen::RowVector3d::Zero());
  return s;
}

// Stretching one sphere no longer trades volume with the other.
TEST(Components, EachKeepsItsOwnVolume) {
  const Scene s = two_spheres_scene();
  for (const Combo& c : kCombos) {
    Deformer d(s.mesh, s.cage);
    ASSERT_EQ(d.rest_part_volumes().size(), 2);
    EXPECT_EQ(d.volume_parts().size(), static_cast<size_t>(s.mesh.F.rows()));
    d.set_options(options_for(c.method, c.mode));
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    const StepResult result = d.solve();
    EXPECT_LE(worst_part_change(d), 1e-6) << c.name << ": " << result.stop_reason;
    ASSERT_EQ(result.iterations.back().part_volume_change.size(), 2u) << c.name;
    std::cout << "[          ] " << c.name << ": volume changes " << result.iterations.back().part_volume_change[0]
              << ", " << result.iterations.back().part_volume_change[1] << "\n";
  }
  // One global volume on request: all triangles in part 0.
  Deformer global(s.mesh, s.cage);
  global.set_volume_parts(std::vector<int>(static_cast<size_t>(s.mesh.F.rows()), 0));
  EXPECT_EQ(global.rest_part_volumes().size(), 1);
  global.set_volume_parts({});
  EXPECT_EQ(global.rest_part_volumes().size(), 2);  // the default again
}

// Reduced integration samples rows of both spheres: each still keeps its own volume.
TEST(Components, ReducedIntegrationKeepsEachVolume) {
  const Scene s = two_spheres_scene();
  for (JacobianMode mode : {JacobianMode::Fast, JacobianMode::Exact}) {
    Deformer d(s.mesh, s.cage);
    const StepResult r = solve_reduced(d, s, mode);
    ASSERT_FALSE(r.iterations.empty());
    EXPECT_GT(r.iterations.front().samples, 0);  // the rule's iterations first (then finishing ones on every vertex)
    EXPECT_LE(worst_part_change(d), 1e-6) << r.stop_reason;
    std::cout << "[          ] reduced/" << (mode == JacobianMode::Fast ? "fast" : "exact") << ": worst volume change "
              << worst_part_change(d) << "\n";
  }
}

// The capped volume of an open mesh and the volumes of two components do not depend on which coordinates
// span the subspace: positive mean value and harmonic coordinates keep them as mean value coordinates do.
TEST(OpenMeshAndComponents, KeepTheirVolumesWithEveryCoordinateType) {
  for (CoordinateType type : {CoordinateType::PositiveMeanValue, CoordinateType::Harmonic}) {
    BasisOptions basis;
    basis.coordinates.type = type;
    basis.coordinates.positive.resolution = 8;
    basis.coordinates.harmonic.resolution = 16;
    for (const Scene& s : {open_capsule_scene(), two_spheres_scene()}) {
      Deformer d(s.mesh, s.cage, basis);
      d.set_options(options_for(Method::Subspace, JacobianMode::Fast));
      d.set_handles(s.groups);
      d.set_targets(s.targets);
      const StepResult r = d.solve();
      EXPECT_TRUE(d.positions().allFinite());
      EXPECT_LE(worst_part_change(d), 1e-6) << coordinate_type_name(type) << ": " << r.stop_reason;
      const int moved = s.groups[1][0];
      EXPECT_GT((d.positions().row(moved) - s.mesh.V.row(moved)).norm(), 0.1) << coordinate_type_name(type);
      std::cout << "[          ] " << coordinate_type_name(type) << ", " << d.rest_part_volumes().size()
                << " part(s): worst volume change " << worst_part_change(d) << " after " << r.iterations.size()
                << " iterations\n";
    }
  }
}

// A scene with every face given its own corners (non-indexed geometry, as exporters write seams), handles and
// targets in that file's numbering; vertex_of: the indexed mesh's vertex of each corner.
struct SplitScene {
  Mesh split;
  std::vector<int> vertex_of;
  std::vector<std::vector<int>> groups;
  Vertices targets;
};

SplitScene split_scene(const Scene& s) {
  Mesh split;
  split.V.resize(3 * s.mesh.F.rows(), 3);
  split.F.resize(s.mesh.F.rows(), 3);
  std::vector<int> vertex_of(static_cast<size_t>(split.V.rows()));
  for (int f = 0; f < s.mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      split.V.row(3 * f + k) = s.mesh.V.row(s.mesh.F(f, k));
      split.F(f, k) = 3 * f + k;
      vertex_of[3 * f + k] = s.mesh.F(f, k);
    }
  // The handles in the split file's numbering: every corner copy of each handle vertex, targets alike.
  std::vector<std::vector<int>> groups(2);
  std::vector<Eigen::RowVector3d> rows;
  int r = 0;
  std::vector<int> row_of(static_cast<size_t>(s.mesh.V.rows()), -1);
  for (size_t g = 0; g < 2; ++g)
    for (int v : s.groups[g]) row_of[v] = r++;
  for (int c = 0; c < split.V.rows(); ++c) {
    const int v = vertex_of[c];
    if (row_of[v] < 0) continue;
    const size_t g = row_of[v] < static_cast<int>(s.groups[0].size()) ? 0 : 1;
    groups[g].push_back(c);
  }
  Vertices targets(static_cast<Eigen::Index>(groups[0].size() + groups[1].size()), 3);
  r = 0;
  for (const auto& g : groups)
    for (int c : g) targets.row(r++) = s.targets.row(row_of[vertex_of[c]]);
  return {split, vertex_of, groups, targets};
}

// Largest distance between a split file's deformed corners and the indexed mesh's deformed vertices.
double corner_gap(const SplitScene& seams, const Deformer& split, const Deformer& welded) {
  double worst = 0;
  for (int corner = 0; corner < seams.split.V.rows(); ++corner)
    worst = std::max(worst, (split.positions().row(corner) - welded.positions().row(seams.vertex_of[corner])).norm());
  return worst;
}

// Every face with its own corners: welded for the solver, the same deformation as the indexed mesh, written
// back per corner.
TEST(SplitVertices, DeformLikeTheWeldedMesh) {
  const Scene s = test::capsule_scene({0.4, -0.4, 0.2});
  const auto [split, vertex_of, groups, targets] = split_scene(s);
  for (const Combo& c : kCombos) {
    Deformer welded(s.mesh, s.cage), seams(split, s.cage);
    EXPECT_EQ(seams.layout().mesh().V.rows(), s.mesh.V.rows());
    welded.set_options(options_for(c.method, c.mode));
    seams.set_options(options_for(c.method, c.mode));
    welded.set_handles(s.groups);
    welded.set_targets(s.targets);
    seams.set_handles(groups);
    seams.set_targets(targets);
    welded.solve();
    seams.solve();
    ASSERT_EQ(seams.positions().rows(), split.V.rows());
    EXPECT_LE(corner_gap({split, vertex_of, groups, targets}, seams, welded), 1e-9 * diagonal(s.mesh)) << c.name;
  }
}

// The same with positive mean value and harmonic coordinates: W is bound on the welded solver mesh, so the split
// file deforms like the indexed one.
TEST(SplitVertices, DeformLikeTheWeldedMeshWithEveryCoordinateType) {
  const Scene s = test::capsule_scene({0.4, -0.4, 0.2});
  const SplitScene seams = split_scene(s);
  for (CoordinateType type : {CoordinateType::PositiveMeanValue, CoordinateType::Harmonic}) {
    BasisOptions basis;
    basis.coordinates.type = type;
    basis.coordinates.positive.resolution = 8;
    basis.coordinates.harmonic.resolution = 16;
    Deformer welded(s.mesh, s.cage, basis), split(seams.split, s.cage, basis);
    EXPECT_EQ(split.coordinates_report().type, type);
    for (Deformer* d : {&welded, &split}) d->set_options(options_for(Method::Subspace));
    welded.set_handles(s.groups);
    welded.set_targets(s.targets);
    split.set_handles(seams.groups);
    split.set_targets(seams.targets);
    EXPECT_TRUE(welded.solve().converged);
    split.solve();
    ASSERT_EQ(split.positions().rows(), seams.split.V.rows());
    EXPECT_LE(corner_gap(seams, split, welded), 1e-9 * diagonal(s.mesh)) << coordinate_type_name(type);
  }
}

// A tetrahedron and one vertex no face uses: check_model and every method accept it, and the vertex moves
// with the surface (a translation of every handle translates it).
TEST(UnreferencedVertices, AreCarriedAlongByEveryMethod) {
  Mesh m;
  m.V.resize(5, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.2, 0.2, 0.2;  // vertex 4 (inside) is used by no face
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  Mesh cage = make_box(3, 3, 3, 1);
  cage.V.rowwise() += Eigen::RowVector3d(0.3, 0.3, 0.3);
  ASSERT_TRUE(check_model_in_cage(MeshLayout(m), cage).ok());
  const Eigen::RowVector3d shift(0.3, -0.2, 0.1);
  Vertices targets = m.V.topRows(4).rowwise() + shift;
  for (Method method : {Method::Subspace, Method::Full, Method::Arap}) {
    Deformer d(m, cage);
    d.set_options(options_for(method));
    d.set_handles({{0, 1, 2, 3}});
    d.set_targets(targets);
    d.solve();
    ASSERT_EQ(d.positions().rows(), 5);
    EXPECT_LE((d.positions().row(4) - (m.V.row(4) + shift)).norm(), 1e-6) << static_cast<int>(method);
  }
  Deformer d(m, cage);
  test::expect_error([&] { d.set_handles({{4}}); }, "which no triangle uses");
}

}  // namespace
}  // namespace sd
