// The Deformer with the spectral basis B (no cage): the rest pose is a fixed point, rigid motions of the handles
// are reproduced exactly, the fast and exact steps reach the same minimizer, the volume is kept, and a genus-1
// mesh deforms.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/mesh/shapes.h"
#include "core/mesh/volume.h"
#include "core/solver/deformer.h"
#include "core/solver/internal/energy/deformation_energy.h"  // max_row_norm
#include "solver_fixtures.h"
#include "test_support.h"

namespace sd {
namespace {

using test::Scene;

const Mesh kNoCage{Vertices(0, 3), Faces(0, 3)};

BasisOptions spectral(int modes) {
  BasisOptions b;
  b.kind = BasisKind::Spectral;
  b.spectral.modes = modes;
  return b;
}

SolverOptions tight(JacobianMode mode) {
  SolverOptions o;
  o.jacobian = mode;
  o.step_tolerance = 1e-11;
  o.merit_tolerance = 1e-15;
  o.max_iterations = 200;
  return o;
}

double bbox(const Mesh& m) { return bounding_box_diagonal(m.V); }

TEST(SpectralSubspace, NeedsNoCageAndTheRestPoseIsAFixedPoint) {
  const Scene s = test::capsule_scene({0, 0, 0});
  Deformer d(s.mesh, kNoCage, spectral(16));
  EXPECT_EQ(d.basis_kind(), BasisKind::Spectral);
  EXPECT_EQ(d.options().method, Method::Subspace) << "the subspace method is available (and the default)";
  EXPECT_EQ(d.basis().cols(), 20);
  EXPECT_EQ(d.subspace_coefficients().rows(), 20);
  EXPECT_EQ(d.basis_eigenvalues().size(), 17);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  for (JacobianMode mode : {JacobianMode::Exact, JacobianMode::Fast}) {
    d.set_options(tight(mode));
    d.reset();
    const StepResult r = d.solve();
    EXPECT_TRUE(r.converged) << r.stop_reason;
    EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.positions() - s.mesh.V)), 1e-12 * bbox(s.mesh));
  }
}

TEST(SpectralSubspace, RigidMotionsOfTheHandlesAreReproducedExactly) {
  Scene s = test::capsule_scene({0, 0, 0});
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::RowVector3d t(0.4, -0.3, 0.2);
  for (Eigen::Index r = 0; r < s.targets.rows(); ++r) s.targets.row(r) = s.targets.row(r) * R.transpose() + t;
  Deformer d(s.mesh, kNoCage, spectral(12));
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  const Vertices expected = (s.mesh.V * R.transpose()).rowwise() + t;
  for (JacobianMode mode : {JacobianMode::Exact, JacobianMode::Fast}) {
    d.set_options(tight(mode));
    d.reset();
    const StepResult r = d.solve();
    EXPECT_TRUE(r.converged) << r.stop_reason;
    EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.positions() - expected)), 1e-8 * bbox(s.mesh))
        << (mode == JacobianMode::Exact ? "exact" : "fast") << " after " << r.iterations.size() << " iterations";
    EXPECT_LE(r.iterations.back().energy, 1e-16);
  }
}

TEST(SpectralSubspace, FastAndExactReachTheSameMinimizerAndKeepTheVolume) {
  const Scene s = test::capsule_scene({0.2, -0.7, 0.1});
  Deformer d(s.mesh, kNoCage, spectral(16));
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  d.set_options(tight(JacobianMode::Exact));
  const StepResult exact = d.solve();
  const Vertices exact_positions = d.positions();
  d.set_options(tight(JacobianMode::Fast));
  d.reset();
  const StepResult fast = d.solve();
  ASSERT_TRUE(exact.converged && fast.converged) << exact.stop_reason << " / " << fast.stop_reason;
  const double e_exact = exact.iterations.back().energy, e_fast = fast.iterations.back().energy;
  EXPECT_NEAR(e_fast, e_exact, 1e-8 * e_exact);
  EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.positions() - exact_positions)), 1e-6 * bbox(s.mesh));
  for (const StepResult* r : {&exact, &fast}) {
    EXPECT_LE(std::abs(r->iterations.back().volume_rel_error), 1e-8);
    for (size_t k = 1; k < r->iterations.size(); ++k)
      EXPECT_LE(r->iterations[k].merit, r->iterations[k - 1].merit * (1 + 1e-12)) << "iteration " << k;
  }
  EXPECT_NEAR(signed_volume(d.positions(), s.mesh.F), d.rest_volume(), 1e-8 * d.rest_volume());
  std::cout << "[          ] spectral k = 16: exact " << exact.iterations.size() << " iterations, fast "
            << fast.iterations.size() << ", energy " << e_exact << " vs " << e_fast << "\n";
}

TEST(SpectralSubspace, AGenusOneTorusDeforms) {
  const Mesh torus = make_torus(1.0, 0.3, 32, 12);
  std::vector<int> left, right;
  for (int i = 0; i < torus.V.rows(); ++i) {
    if (torus.V(i, 0) < -1.1) left.push_back(i);
    if (torus.V(i, 0) > 1.1) right.push_back(i);
  }
  Deformer d(torus, kNoCage, spectral(20));
  d.set_handles({left, right});
  Vertices targets(static_cast<Eigen::Index>(left.size() + right.size()), 3);
  int row = 0;
  for (int v : left) targets.row(row++) = torus.V.row(v);
  for (int v : right) targets.row(row++) = torus.V.row(v) + Eigen::RowVector3d(0.3, 0.0, 0.4);
  d.set_targets(targets);
  const StepResult r = d.solve();
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_LE(std::abs(r.iterations.back().volume_rel_error), 1e-8);
  const double moved = (d.positions().row(right[0]) - torus.V.row(right[0])).norm();
  EXPECT_GT(moved, 0.25) << "the pulled side follows its handle (soft, 0.5 away)";
}

TEST(SpectralSubspace, RefusesTooManyModesBeforeAnySession) {
  const Mesh small = make_icosphere(1, 1.0);
  test::expect_error([&] { Deformer d(small, kNoCage, spectral(100)); }, "must be from 1 to 37");
}

}  // namespace
}  // namespace sd
