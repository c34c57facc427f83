// Components no handle holds (core/solver/internal/energy/component_anchors.h): two capsules side by side, handles on
// the first only. The energy cannot see the second one's rigid motions, so before the anchors the spectral basis threw
// it 290 units away ("converged") or failed to factor blaming a cage it does not have. It must stay put in the full
// space and ARAP, nearly so in the spectral basis, and follow the cage in the cage subspace.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "core/mesh/shapes.h"
#include "core/mesh/volume.h"
#include "core/solver/deformer.h"
#include "core/solver/internal/energy/component_anchors.h"
#include "core/solver/internal/energy/deformation_energy.h"  // max_row_norm
#include "solver_fixtures.h"
#include "test_support.h"

namespace sd {
namespace {

// The capsule scene's mesh and a copy 1.5 away in z; the handles (the first capsule's ends) and targets as there.
struct TwoCapsules {
  test::Scene scene = test::capsule_scene({0.0, -0.6, 0.3});
  Mesh both;
  int first = 0;  // vertices of the first capsule
  TwoCapsules() {
    Mesh second = scene.mesh;
    second.V.col(2).array() += 1.5;
    both = test::join_meshes(scene.mesh, second);
    first = static_cast<int>(scene.mesh.V.rows());
  }
  // The largest move of the second capsule's vertices.
  double second_moved(const Vertices& X) const {
    return max_row_norm(Eigen::MatrixXd(X.bottomRows(X.rows() - first) - both.V.bottomRows(X.rows() - first)));
  }
};

BasisOptions spectral(int modes) {
  BasisOptions b;
  b.kind = BasisKind::Spectral;
  b.spectral.modes = modes;
  return b;
}

TEST(ComponentAnchors, ThreeSpreadVerticesOfEachComponentWithoutHandles) {
  const TwoCapsules t;
  EXPECT_TRUE(component_anchors(t.both.V, t.both.F, {0, t.first}).empty());  // both held
  const auto anchors = component_anchors(t.both.V, t.both.F, {0});
  ASSERT_EQ(anchors.size(), 1u);
  ASSERT_EQ(anchors[0].size(), 3u);
  for (int v : anchors[0]) EXPECT_GE(v, t.first);  // on the second capsule
  const Eigen::RowVector3d a = t.both.V.row(anchors[0][0]), b = t.both.V.row(anchors[0][1]),
                           c = t.both.V.row(anchors[0][2]);
  EXPECT_GT((b - a).cross(c - a).norm(), 0.1);  // not collinear: they pin rotations too
}

TEST(FreeComponent, StaysPutInTheSpectralBasisTheFullSpaceAndArap) {
  const TwoCapsules t;
  const Mesh no_cage{Vertices(0, 3), Faces(0, 3)};
  Deformer d(t.both, no_cage, spectral(24));
  d.set_handles(t.scene.groups);
  d.set_targets(t.scene.targets);
  for (Method method : {Method::Subspace, Method::Full, Method::Arap})
    for (EnergyWeighting weighting : {EnergyWeighting::Area, EnergyWeighting::Uniform}) {
      SolverOptions o;
      o.method = method;
      o.weighting = weighting;
      d.set_options(o);
      d.reset();
      const StepResult r = d.solve();
      SCOPED_TRACE(std::to_string(static_cast<int>(method)) +
                   (weighting == EnergyWeighting::Area ? " area" : " uniform"));
      EXPECT_TRUE(r.converged) << r.stop_reason;
      // The spectral modes span both capsules (identical shapes have identical spectra), so moving the first one
      // moves the second a little through them, which three anchors resist but cannot cancel: measured 0.6% (area)
      // and 0.3% (uniform) of the diagonal. The full space and ARAP hold it exactly.
      const double held = method == Method::Subspace ? 1e-2 * bounding_box_diagonal(t.both.V) : 1e-6;
      EXPECT_LE(t.second_moved(d.positions()), held);
      EXPECT_LE(d.handle_distances().maxCoeff(), 0.05);  // the first capsule still follows its handles
      if (method != Method::Arap) EXPECT_LE(std::abs(r.iterations.back().volume_rel_error), 1e-9);
    }
}

TEST(FreeComponent, FollowsTheCageInTheCageSubspace) {
  const TwoCapsules t;
  Mesh cage = make_bar_cage(-1.6, 1.6, 0.6, 1.3, 4);  // around both capsules
  cage.V.col(2).array() += 0.75;
  Deformer d(t.both, cage);
  d.set_handles(t.scene.groups);
  d.set_targets(t.scene.targets);
  const StepResult r = d.solve();
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_GT(t.second_moved(d.positions()), 1e-3);  // carried along by the cage, not anchored at rest
}

// A closed part a thousandth of the model's size and no handle on it (a rivet on a body: an attack's sphere of radius
// 1e-3 beside one of radius 1). Its restoring direction N^-1 c is as small as its volume's gradient, and the
// restoration's slope called the two parts' system singular, so no trial was restored and every solve stalled at rest
// (volume_restoration.cpp, SlopeSolver). Both parts must keep their volumes and the handles be met.
TEST(FreeComponent, ATinyPartBesideALargeOneKeepsBothVolumesAndLetsTheSolveMove) {
  const TwoCapsules t;
  Mesh tiny = t.scene.mesh;
  const Eigen::RowVector3d centre = tiny.V.colwise().mean();
  tiny.V = ((tiny.V.rowwise() - centre) * 1e-3).rowwise() + Eigen::RowVector3d(0.0, 0.0, 1.0);
  const Mesh both = test::join_meshes(t.scene.mesh, tiny);
  const Faces first_faces = t.scene.mesh.F;
  const Faces tiny_faces = (tiny.F.array() + t.first).matrix();
  const Mesh no_cage{Vertices(0, 3), Faces(0, 3)};
  Mesh cage = make_bar_cage(-1.6, 1.6, 0.6, 1.3, 4);  // around both, as in FollowsTheCageInTheCageSubspace
  cage.V.col(2).array() += 0.75;
  for (const char* basis : {"full space", "spectral", "cage"}) {
    const std::string b = basis;
    auto made = b == "spectral" ? std::make_unique<Deformer>(both, no_cage, spectral(24))
                                : std::make_unique<Deformer>(both, b == "cage" ? cage : no_cage);
    Deformer& d = *made;
    SolverOptions o;
    o.method = b == "full space" ? Method::Full : Method::Subspace;
    d.set_options(o);
    d.set_handles(t.scene.groups);
    d.set_targets(t.scene.targets);
    const StepResult r = d.solve();
    SCOPED_TRACE(b);
    EXPECT_TRUE(r.converged) << r.stop_reason;
    EXPECT_LE(d.handle_distances().maxCoeff(), 0.05);  // it moved: at rest the handles are 0.67 off
    // Each part's volume summed about its own centre: about the origin the tiny part's would lose its digits.
    const auto volume = [](const Vertices& X, const Faces& F, const Eigen::RowVector3d& about) {
      return signed_volume(Vertices(X.rowwise() - about), F);
    };
    const Eigen::RowVector3d tiny_centre(0.0, 0.0, 1.0);
    EXPECT_NEAR(volume(d.positions(), first_faces, centre) / volume(both.V, first_faces, centre), 1.0, 1e-9);
    EXPECT_NEAR(volume(d.positions(), tiny_faces, tiny_centre) / volume(both.V, tiny_faces, tiny_centre), 1.0, 1e-9);
    const Eigen::VectorXd kept = d.part_volumes().cwiseQuotient(d.rest_part_volumes());
    EXPECT_LE((kept.array() - 1.0).abs().maxCoeff(), 1e-9)
        << kept.transpose() << " " << r.stop_reason << " its " << r.iterations.size() << " last "
        << r.iterations.back().volume_rel_error;
  }
}

}  // namespace
}  // namespace sd
