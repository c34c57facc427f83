// The projection constraint (core/solver/handle_line.h): a handle held only across its lines, its depth left to
// the energy. Derivatives by finite differences, the depth's freedom, the comparison with a point target the
// issue asks for (on the line at least as well, energy no higher), the volume, every method and integration
// reaching the same shape, and the errors.
#include "core/solver/handle_line.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/mesh/examples.h"
#include "core/mesh/volume.h"
#include "core/solver/deformer.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "solver_fixtures.h"
#include "test_support.h"

namespace sd {
namespace {

using test::Scene;

// The capsule bent down (and pulled towards the viewer, which a line along z ignores).
Scene bent_capsule() { return test::capsule_scene({0.0, -0.6, 0.5}); }

SolverOptions options_for(Method method, JacobianMode mode, Integration integration = Integration::Full) {
  SolverOptions o;
  o.method = method;
  o.jacobian = mode;
  o.integration = integration;
  return o;
}

// The moved group's vertices, each its distance from its line (point target: from the target).
double worst_distance(const Deformer& d) { return d.handle_distances().maxCoeff(); }

TEST(HandleLine, DirectionsAreUnitAndFollowTheTarget) {
  const Eigen::RowVector3d t(1, 2, 3);
  EXPECT_TRUE(line_direction(HandleLine{}, t).isZero());
  EXPECT_NEAR((line_direction(HandleLine::along({0, 0, -4}), t) - Eigen::RowVector3d(0, 0, -1)).norm(), 0, 1e-15);
  EXPECT_NEAR((line_direction(HandleLine::from({1, 2, 13}), t) - Eigen::RowVector3d(0, 0, -1)).norm(), 0, 1e-15);
  EXPECT_TRUE(line_direction(HandleLine::from({1, 2, 3}), t).isZero());  // eye at the target: a point target
  // Any nonzero, finite length gives the same line: the norms of these overflow and underflow unscaled.
  for (double size : {1e155, 1e300, 1e-200, 5e-324}) {
    EXPECT_NEAR((line_direction(HandleLine::along({0, 0, -size}), t) - Eigen::RowVector3d(0, 0, -1)).norm(), 0, 1e-15)
        << size;
    validate_handle_line(HandleLine::along({0, 0, size}), "test");  // nonzero: no throw
  }
  EXPECT_NEAR((line_direction(HandleLine::from({1, 2, 1e155}), t) - Eigen::RowVector3d(0, 0, -1)).norm(), 0, 1e-15);
}

TEST(HandleLine, EnergyGradientMatchesFiniteDifferencesAndIgnoresDepth) {
  const Scene s = bent_capsule();
  DeformationEnergy energy(s.mesh.V, s.mesh.F);
  energy.set_handles(test::flat_handles(s),
                     {static_cast<int>(s.groups[0].size()), static_cast<int>(s.groups[1].size())});
  energy.set_targets(s.targets);
  std::vector<HandleLine> lines(s.groups[0].size(), HandleLine{});
  lines.resize(s.targets.rows(), HandleLine::from({0.3, 0.2, 6.0}));
  energy.set_handle_lines(lines);
  Vertices X = s.mesh.V;
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    X.row(i) += 0.05 * Eigen::RowVector3d(std::sin(3.0 * i), std::cos(i), 0.5);
  const EnergyJacobian J = energy.jacobian(X);
  const Eigen::MatrixXd g = J.gradient(energy.evaluate(X));
  const double error = test::gradient_error(X, g, [&](const Eigen::MatrixXd& Y) { return energy.evaluate(Y).energy; });
  EXPECT_LE(error, 1e-6 * g.cwiseAbs().maxCoeff());
  // J^T J applied to a direction: the derivative of the gradient along it (the handle rows are linear).
  const Eigen::MatrixXd v = Eigen::MatrixXd::Random(X.rows(), 3);
  const double h = 1e-6;
  const Eigen::MatrixXd fd =
      (J.gradient(energy.evaluate(X + h * v)) - J.gradient(energy.evaluate(X - h * v))) / (2 * h);
  const Eigen::MatrixXd JtJv = J.normal_product(v);
  for (int k : s.groups[1]) EXPECT_LE((fd.row(k) - JtJv.row(k)).norm(), 1e-6 * JtJv.norm()) << "vertex " << k;
  // Moving a handle vertex along its line leaves the handle term unchanged.
  const int k = s.groups[1][0];
  const Eigen::Index row = static_cast<Eigen::Index>(s.groups[0].size());
  Vertices Y = X;
  Y.row(k) += 0.7 * energy.line_directions().row(row);
  EXPECT_NEAR(energy.evaluate(Y).position_energy, energy.evaluate(X).position_energy, 1e-12);
}

// The handle term is soft: freeing the depth moves its balance with the Laplacian term a little either way (on the
// bar of the JS tests 0.97-1.03 of the point target's distance; here 0.77), while the energy always drops.
TEST(HandleLine, MeetsItsLinesAboutAsWellAsAPointTargetWithLessEnergy) {
  const Scene s = bent_capsule();
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  ASSERT_TRUE(d.solve().converged);
  const double point_distance = worst_distance(d), point_energy = d.full_energy();
  d.set_handle_lines({HandleLine{}, HandleLine::along({0, 0, 1})});
  const StepResult r = d.solve();
  ASSERT_TRUE(r.converged) << r.stop_reason;
  EXPECT_LE(worst_distance(d), point_distance * 1.05);
  EXPECT_LE(d.full_energy(), point_energy * (1 + 1e-9));
  EXPECT_LT(d.full_energy(), 0.9 * point_energy);  // the depth it was asked for (z + 0.5) cost energy
  EXPECT_NEAR(signed_volume(d.positions(), s.mesh.F), d.rest_volume(), 1e-9 * d.rest_volume());
  std::cout << "[          ] point target: distance " << point_distance << ", energy " << point_energy
            << "; along z: distance " << worst_distance(d) << ", energy " << d.full_energy() << "\n";
}

// Targets slid along their lines name the same lines: the same shape, whatever depth the targets had.
TEST(HandleLine, TheTargetsDepthDoesNotMatter) {
  for (const HandleLine& line : {HandleLine::along({0.2, 0.1, 1.0}), HandleLine::from({0.5, -0.2, 7.0})}) {
    const Scene s = bent_capsule();
    Deformer d(s.mesh, s.cage);
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    d.set_handle_lines({HandleLine{}, line});
    ASSERT_TRUE(d.solve().converged);
    const Vertices first = d.positions();
    Vertices slid = s.targets;
    for (Eigen::Index r = static_cast<Eigen::Index>(s.groups[0].size()); r < slid.rows(); ++r)
      slid.row(r) += 0.8 * line_direction(line, s.targets.row(r));
    d.reset();
    d.set_targets(slid);
    ASSERT_TRUE(d.solve().converged);
    EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.positions() - first)), 1e-5 * bounding_box_diagonal(s.mesh.V))
        << (line.kind == HandleLine::Kind::Along ? "along" : "from");
  }
}

TEST(HandleLine, EveryMethodAndIntegrationReachesTheSameShapeAndKeepsTheVolume) {
  const Scene s = bent_capsule();
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  d.set_handle_lines({HandleLine{}, HandleLine::from({0.0, 0.0, 8.0})});
  const struct {
    SolverOptions options;
    const char* name;
  } runs[] = {{options_for(Method::Subspace, JacobianMode::Fast), "subspace/fast"},
              {options_for(Method::Subspace, JacobianMode::Exact), "subspace/exact"},
              {options_for(Method::Subspace, JacobianMode::Fast, Integration::Reduced), "subspace/fast/reduced"},
              {options_for(Method::Subspace, JacobianMode::Exact, Integration::Reduced), "subspace/exact/reduced"}};
  Vertices reference;
  for (const auto& run : runs) {
    d.set_options(run.options);
    d.reset();
    const StepResult r = d.solve();
    EXPECT_TRUE(r.converged) << run.name << ": " << r.stop_reason;
    EXPECT_LE(std::abs(r.iterations.back().volume_rel_error), 1e-9) << run.name;
    for (size_t k = 1; k < r.iterations.size(); ++k)
      EXPECT_LE(r.iterations[k].merit, r.iterations[k - 1].merit * (1 + 1e-12)) << run.name << " iteration " << k;
    if (reference.size() == 0) reference = d.positions();
    // The capsule has fewer vertices than the reduced rule's samples: reduced integration sums every vertex.
    EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.positions() - reference)), 1e-5 * bounding_box_diagonal(s.mesh.V))
        << run.name;
  }
  // The full space has more freedom: a different shape, held the same way.
  for (JacobianMode mode : {JacobianMode::Fast, JacobianMode::Exact}) {
    d.set_options(options_for(Method::Full, mode));
    d.reset();
    const StepResult r = d.solve();
    EXPECT_TRUE(r.converged) << r.stop_reason;
    EXPECT_LE(std::abs(r.iterations.back().volume_rel_error), 1e-9);
    EXPECT_LE(worst_distance(d), 0.1);
  }
}

// Every handle on a line along the same direction: the whole mesh may slide along it (no handle fixes the depth).
// The solve still ends on the lines, with the volume, in every mode.
TEST(HandleLine, OnlyLinesHoldTheMesh) {
  const Scene s = bent_capsule();
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  d.set_handle_lines({HandleLine::along({0, 0, 1}), HandleLine::along({0, 0, 1})});
  for (const test::Combo& c : test::kCombos) {
    d.set_options(options_for(c.method, c.mode));
    d.reset();
    const StepResult r = d.solve();
    EXPECT_TRUE(d.positions().allFinite()) << c.name;
    EXPECT_NE(r.stop, StopCode::NumericalFailure) << c.name << ": " << r.stop_reason;
    EXPECT_LE(std::abs(r.iterations.back().volume_rel_error), 1e-9) << c.name;
    EXPECT_LE(worst_distance(d), 0.1) << c.name;
  }
}

// A perspective drag: the eye's lines turn with the targets every frame, so each frame is a slightly different
// problem (with the eye 1000x further, nearly parallel lines: 1.25 products per frame, as a point target). Measured
// on the built-in bar: the subspace 3.3 products per frame either way; the full space 12.4 with its preconditioner's
// directions kept from the first frame, 7.7 with it remade once the lines have turned by 2 degrees.
TEST(HandleLine, APerspectiveDragStaysCheap) {
  const Example bar = make_example("bar");
  std::vector<int> left, right;
  for (int i = 0; i < bar.mesh.V.rows(); ++i) {
    if (bar.mesh.V(i, 0) < -2.2) left.push_back(i);
    if (bar.mesh.V(i, 0) > 2.2) right.push_back(i);
  }
  for (Method method : {Method::Subspace, Method::Full}) {
    Deformer d(bar.mesh, bar.cage);
    SolverOptions o;
    o.method = method;
    d.set_options(o);
    d.set_handles({left, right});
    double products = 0;
    const int frames = 40;
    for (int f = 0; f < frames; ++f) {
      const double s = std::sin(3.14159265358979 * f / 20.0);
      Vertices targets(static_cast<Eigen::Index>(left.size() + right.size()), 3);
      Eigen::Index r = 0;
      for (int v : left) targets.row(r++) = bar.mesh.V.row(v);
      for (int v : right) targets.row(r++) = bar.mesh.V.row(v) + Eigen::RowVector3d(0, -0.8 * s, 0.3 * s);
      d.set_targets(targets);
      d.set_handle_lines({HandleLine{}, HandleLine::from({0, 0, 12})});
      const StepResult step = d.step(1);
      products += step.iterations.empty() ? 0 : step.iterations.back().products;
    }
    std::cout << "[          ] " << (method == Method::Subspace ? "subspace" : "full") << ": " << products / frames
              << " products per frame\n";
    EXPECT_LE(products / frames, method == Method::Subspace ? 4.0 : 9.0)
        << (method == Method::Subspace ? "subspace" : "full");
  }
}

TEST(HandleLine, BadLinesThrowAndLeaveTheLinesUnchanged) {
  const Scene s = bent_capsule();
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  const std::vector<HandleLine> good{HandleLine{}, HandleLine::along({0, 0, 1})};
  d.set_handle_lines(good);
  test::expect_error([&] { d.set_handle_lines({HandleLine{}}); }, "1 lines for 2 handle groups");
  test::expect_error([&] { d.set_handle_lines({HandleLine{}, HandleLine::along({0, 0, 0})}); }, "nonzero direction");
  test::expect_error([&] { d.set_handle_lines({HandleLine{}, HandleLine::from({0, NAN, 0})}); }, "3 finite numbers");
  EXPECT_TRUE(d.handle_lines() == good);
  d.set_handles(s.groups);  // a new handle set: point targets again
  EXPECT_TRUE(d.handle_lines().empty());
}

}  // namespace
}  // namespace sd
