// The Deformer session: rest pose, rigid translation, volume, warm start, method switching, handle and
// target validation, the NaN guard, and convergence on real models from ../shared/data.
#include "core/solver/deformer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/solver/internal/energy/deformation_energy.h"
#include "core/error.h"
#include "core/mesh/examples.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/volume.h"
#include "solver_fixtures.h"
#include "test_support.h"

namespace sd {
namespace {

using test::Scene;

SolverOptions options_for(Method method, JacobianMode mode, bool volume = true) {
  SolverOptions o;
  o.method = method;
  o.jacobian = mode;
  o.volume = volume;
  return o;
}

double bbox(const Mesh& m) { return bounding_box_diagonal(m.V); }

using test::Combo;
using test::kCombos;

TEST(Deformer, RestPoseIsAFixedPointInEveryMode) {
  const Scene s = test::capsule_scene({0, 0, 0});
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  for (const Combo& c : kCombos) {
    d.set_options(options_for(c.method, c.mode));
    const StepResult r = d.solve();
    EXPECT_TRUE(r.converged) << c.name << ": " << r.stop_reason;
    EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.positions() - s.mesh.V)), 1e-10 * bbox(s.mesh)) << c.name;
  }
}

TEST(Deformer, SameTranslationOfEveryHandleIsRigid) {
  const Eigen::RowVector3d t(0.3, -0.2, 0.1);
  Scene s = test::capsule_scene({0, 0, 0});
  for (Eigen::Index r = 0; r < s.targets.rows(); ++r) s.targets.row(r) += t;
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  for (const Combo& c : kCombos) {
    d.set_options(options_for(c.method, c.mode));
    d.reset();
    const StepResult r = d.solve();
    EXPECT_TRUE(r.converged) << c.name << ": " << r.stop_reason;
    Vertices expected = s.mesh.V;
    expected.rowwise() += t;
    EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.positions() - expected)), 1e-6 * bbox(s.mesh))
        << c.name << " after " << r.iterations.size() << " iterations";
    if (c.method == Method::Subspace) {
      Vertices cage = s.cage.V;
      cage.rowwise() += t;
      EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.cage_positions() - cage)), 1e-6 * bbox(s.mesh)) << c.name;
    }
  }
}

TEST(Deformer, BendConservesVolumeAndMeritNeverIncreases) {
  const Scene s = test::capsule_scene({0.0, -0.7, 0.2});
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  for (const Combo& c : kCombos) {
    d.set_options(options_for(c.method, c.mode));
    d.reset();
    const StepResult r = d.solve();
    ASSERT_FALSE(r.iterations.empty());
    EXPECT_TRUE(r.converged) << c.name << ": " << r.stop_reason;
    EXPECT_LE(std::abs(r.iterations.back().volume_rel_error), 1e-8) << c.name;
    EXPECT_NEAR(signed_volume(d.positions(), s.mesh.F), d.rest_volume(), 1e-8 * d.rest_volume()) << c.name;
    for (size_t k = 1; k < r.iterations.size(); ++k)
      EXPECT_LE(r.iterations[k].merit, r.iterations[k - 1].merit * (1 + 1e-12)) << c.name << " iteration " << k;
    EXPECT_TRUE(d.positions().allFinite());
    std::cout << "[          ] " << c.name << ": " << r.iterations.size() << " iterations, energy "
              << r.iterations.back().energy << ", " << r.stop_reason << "\n";
  }
}

// The preconditioner's memory of earlier products (cgMemory) changes how many products a solve takes,
// never where it ends; reset() forgets it, so a solve after a reset repeats exactly.
// prepare_factor() makes the factor preconditioner's pose-free parts before a solve needs them (the app: at load). It
// only moves that work: the solve that buys the factor takes the same iterations, products and bits.
TEST(Deformer, PreparingTheFactorBeforeTheSolveChangesNothingButWhen) {
  // A capsule of about 4000 vertices (deformer_threads_test.cpp's), on which a tight PCG tolerance buys the factor.
  const Scene s = test::capsule_scene({0.0, -0.7, 0.2}, 8, 60, 48, 8);
  const auto solve = [&](Preconditioner preconditioner, bool prepare) {
    Deformer d(s.mesh, s.cage);
    SolverOptions o = options_for(Method::Subspace, JacobianMode::Fast);
    o.preconditioner = preconditioner;
    o.cg_tolerance = 1e-8;  // runs long enough to make the factor
    d.set_options(o);
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    if (prepare) d.prepare_factor();
    const StepResult r = d.solve();
    std::vector<int> products;
    for (const IterationStats& it : r.iterations) products.push_back(it.products);
    return std::make_pair(d.positions(), products);
  };
  const auto [lazy, lazy_products] = solve(Preconditioner::GaussNewton, false);
  const auto [prepared, prepared_products] = solve(Preconditioner::GaussNewton, true);
  EXPECT_EQ(prepared, lazy);
  EXPECT_EQ(prepared_products, lazy_products);
  // The factor was bought in this solve: without it (the constant preconditioner) the products differ.
  EXPECT_NE(solve(Preconditioner::Constant, false).second, lazy_products);
  // The parts are made, and kept until the weighting changes (a new subspace method).
  Deformer d(s.mesh, s.cage);
  SolverOptions o = options_for(Method::Subspace, JacobianMode::Fast);
  d.set_options(o);
  EXPECT_FALSE(d.factor_prepared());
  d.prepare_factor();
  EXPECT_TRUE(d.factor_prepared());
  o.weighting = EnergyWeighting::Uniform;
  d.set_options(o);
  EXPECT_FALSE(d.factor_prepared());
  // Where no factor can be bought (the constant preconditioner, ARAP) there is nothing to make, and no error.
  o.preconditioner = Preconditioner::Constant;
  d.set_options(o);
  d.prepare_factor();
  EXPECT_FALSE(d.factor_prepared());
  d.set_options(options_for(Method::Arap, JacobianMode::Fast));
  EXPECT_NO_THROW(d.prepare_factor());
  EXPECT_FALSE(d.factor_prepared());
}

TEST(Deformer, PreconditionerMemoryKeepsTheMinimizerAndResetForgetsIt) {
  const Scene s = test::capsule_scene({0.0, -0.7, 0.2});
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  SolverOptions o = options_for(Method::Subspace, JacobianMode::Fast);
  o.cg_memory = 0;
  d.set_options(o);
  const StepResult plain = d.solve();
  const Vertices plain_positions = d.positions();
  o.cg_memory = 16;
  d.set_options(o);
  d.reset();
  const StepResult first = d.solve();
  EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.positions() - plain_positions)), 1e-6 * bbox(s.mesh));
  EXPECT_NEAR(first.iterations.back().energy, plain.iterations.back().energy, 1e-9 * plain.iterations.back().energy);
  d.reset();
  const StepResult again = d.solve();
  ASSERT_EQ(again.iterations.size(), first.iterations.size());
  for (size_t k = 0; k < first.iterations.size(); ++k)
    EXPECT_EQ(again.iterations[k].products, first.iterations[k].products) << "iteration " << k;
  int products_plain = 0, products_memory = 0;
  for (const auto& it : plain.iterations) products_plain += it.products;
  for (const auto& it : first.iterations) products_memory += it.products;
  std::cout << "[          ] products: " << products_plain << " without memory, " << products_memory
            << " with 16 pairs\n";
  EXPECT_LE(products_memory, products_plain);
}

// Two handles of one vertex each leave the rotation about the line through them free: the Gauss-Newton
// matrix is only semidefinite at rest. Every mode must still take the step (the exact subspace mode used to
// refuse to factor it) and pull the moved vertex to its target.
TEST(Deformer, TwoSingleVertexHandlesWorkInEveryMode) {
  Scene s = test::capsule_scene({0, 0, 0});
  const int left = s.groups[0].front(), right = s.groups[1].front();
  Deformer d(s.mesh, s.cage);
  d.set_handles({{left}, {right}});
  Vertices targets(2, 3);
  targets.row(0) = s.mesh.V.row(left);
  targets.row(1) = s.mesh.V.row(right) + Eigen::RowVector3d(0.0, -0.3, 0.1);
  d.set_targets(targets);
  for (const Combo& c : kCombos) {
    d.set_options(options_for(c.method, c.mode));
    d.reset();
    const StepResult r = d.solve();
    EXPECT_TRUE(r.converged) << c.name << ": " << r.stop_reason;
    EXPECT_TRUE(d.positions().allFinite()) << c.name;
    // Soft handles (w_pos = 1) stop short of the target; they must still move most of the way.
    const double moved = (d.positions().row(right) - s.mesh.V.row(right)).norm();
    EXPECT_GT(moved, 0.5 * 0.3162) << c.name;
    EXPECT_NEAR(signed_volume(d.positions(), s.mesh.F), d.rest_volume(), 1e-8 * d.rest_volume()) << c.name;
  }
}

// A 120-degree rotation of one end of the built-in bar about the other (report fig. 4 style). The first
// full-space step is long enough to fold the bar; that trial must be rejected (its volume cannot be
// restored), not accepted because lambda g lowers the merit. Before that rule the full space "converged" at
// -104% volume here.
TEST(Deformer, LargeRotationKeepsTheVolumeInEveryMode) {
  const Example bar = make_example("bar");
  Scene s{bar.mesh, bar.cage, {}, {}};
  s.groups.push_back(test::vertices_where(s.mesh, [](const Eigen::RowVector3d& p) { return p.x() < -2.2; }));
  s.groups.push_back(test::vertices_where(s.mesh, [](const Eigen::RowVector3d& p) { return p.x() > 2.2; }));
  const Eigen::Matrix3d R = Eigen::AngleAxisd(120.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::RowVector3d center(-2.4, 0.0, 0.0);
  s.targets.resize(static_cast<int>(s.groups[0].size() + s.groups[1].size()), 3);
  int row = 0;
  for (int v : s.groups[0]) s.targets.row(row++) = s.mesh.V.row(v);
  for (int v : s.groups[1]) s.targets.row(row++) = center + (s.mesh.V.row(v) - center) * R.transpose();
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  for (const Combo& c : kCombos) {
    if (c.method == Method::Full && c.mode == JacobianMode::Exact)
      continue;  // a sparse factorization per iteration: slow here
    d.set_options(options_for(c.method, c.mode));
    d.reset();
    const StepResult r = d.solve();
    ASSERT_FALSE(r.iterations.empty()) << c.name << ": " << r.stop_reason;
    EXPECT_NEAR(signed_volume(d.positions(), s.mesh.F), d.rest_volume(), 1e-8 * d.rest_volume()) << c.name;
    EXPECT_TRUE(d.positions().allFinite()) << c.name;
    std::cout << "[          ] " << c.name << ": " << r.iterations.size() << " iterations, energy "
              << r.iterations.back().energy << ", " << r.stop_reason << "\n";
  }
}

TEST(Deformer, VolumeVisiblyChangesWhenTheConstraintIsOff) {
  const Scene s = test::capsule_scene({-0.6, 0.0, 0.0});  // squash
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  d.set_options(options_for(Method::Subspace, JacobianMode::Fast, false));
  const StepResult off = d.solve();
  const double off_error = (signed_volume(d.positions(), s.mesh.F) - d.rest_volume()) / d.rest_volume();
  d.set_options(options_for(Method::Subspace, JacobianMode::Fast, true));
  const StepResult on = d.solve();  // continues from the unconstrained result and restores the volume
  EXPECT_TRUE(off.converged && on.converged) << off.stop_reason << " / " << on.stop_reason;
  EXPECT_GE(std::abs(off_error), 1e-2);
  EXPECT_LE(std::abs(on.iterations.back().volume_rel_error), 1e-8);
}

TEST(Deformer, WarmStartedStepsReachTheSolveResult) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  const StepResult full = d.solve();
  const Vertices solved = d.positions();
  d.reset();
  EXPECT_EQ(d.positions(), s.mesh.V);
  int iterations = 0;
  StepResult r;
  do {
    r = d.step(1);
    iterations += static_cast<int>(r.iterations.size());
  } while (!r.converged && iterations < 100);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations.empty() ? -1 : r.iterations.back().iteration, iterations) << "iterations count from the reset";
  EXPECT_LE(max_row_norm(Eigen::MatrixXd(d.positions() - solved)), 1e-6 * bbox(s.mesh));
  // Dragging: new targets continue from the current positions and take few iterations.
  Vertices targets = s.targets;
  for (Eigen::Index k = 0; k < targets.rows(); ++k)
    if (k >= static_cast<Eigen::Index>(s.groups[0].size())) targets(k, 1) -= 0.02;
  d.set_targets(targets);
  const StepResult drag = d.solve();
  EXPECT_TRUE(drag.converged);
  EXPECT_LE(drag.iterations.size(), full.iterations.size() + 2);
}

TEST(Deformer, BadHandlesThrowAndLeaveTheSessionUnchanged) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  d.step(2);
  const Vertices before = d.positions();
  const int n = static_cast<int>(s.mesh.V.rows());
  const std::vector<std::pair<std::vector<std::vector<int>>, std::string>> bad = {
      {{{0, 1}, {}}, "group 1 is empty"},
      {{{0, n}}, "outside [0, " + std::to_string(n) + ")"},
      {{{-1}}, "vertex -1 outside"},
      {{{3, 4, 3}}, "vertex 3 appears twice in group 0"},
      {{{3, 4}, {5, 4}}, "vertex 4 is in both group 0 and group 1"},
  };
  for (const auto& [groups, message] : bad) {
    try {
      d.set_handles(groups);
      ADD_FAILURE() << "no error for " << message;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
    EXPECT_EQ(d.handles(), s.groups);
    EXPECT_EQ(d.positions(), before);
  }
  // Still usable with the old handles and targets.
  const StepResult r = d.solve();
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_GT(max_row_norm(Eigen::MatrixXd(d.positions() - before)), 0.0);
}

TEST(Deformer, BadTargetsAndOptionsThrow) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  EXPECT_THROW(d.set_targets(Vertices::Zero(3, 3)), Error);
  Vertices nan_targets = s.targets;
  nan_targets(2, 1) = std::nan("");
  try {
    d.set_targets(nan_targets);
    ADD_FAILURE() << "NaN target accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
  SolverOptions o;
  o.position_weight = -1;
  EXPECT_THROW(d.set_options(o), Error);
  EXPECT_EQ(d.options().position_weight, 1.0);
  o = SolverOptions();
  o.armijo_c2 = 1.5;
  EXPECT_THROW(d.set_options(o), Error);
  // A PCG tolerance below what doubles resolve cannot be met: refused, naming the limit.
  o = SolverOptions();
  o.cg_tolerance = 1e-17;
  try {
    d.set_options(o);
    ADD_FAILURE() << "cgTolerance 1e-17 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("[1e-12, 1)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(d.step(-1), Error);
}

TEST(Deformer, NonFiniteEnergyKeepsTheLastGoodIterate) {
  Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  d.step(1);
  const Vertices good = d.positions();
  s.targets.array() *= 1e200;  // finite targets whose energy overflows to Inf
  d.set_targets(s.targets);
  for (const Combo& c : kCombos) {
    d.set_options(options_for(c.method, c.mode));
    const StepResult r = d.step(3);
    EXPECT_FALSE(r.converged) << c.name;
    EXPECT_EQ(r.stop_reason.rfind("numerical failure", 0), 0u) << c.name << ": " << r.stop_reason;
    EXPECT_EQ(r.stop, StopCode::NumericalFailure) << c.name;
    EXPECT_TRUE(d.positions().allFinite()) << c.name;
  }
  d.set_options(options_for(Method::Subspace, JacobianMode::Fast));
  d.set_targets(s.targets / 1e200);
  d.solve();
  EXPECT_TRUE(d.positions().allFinite());
  (void)good;
}

// The code of the sd::Error that body() throws (fails the test when it throws none).
template <typename Body>
ErrorCode code_of(Body body) {
  try {
    body();
  } catch (const Error& e) {
    return e.code();
  }
  ADD_FAILURE() << "no sd::Error thrown";
  return ErrorCode::Internal;
}

TEST(Deformer, FailuresCarryTheirCodes) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Mesh moved = s.cage;
  moved.V.col(0).array() += 1.0;  // the mesh's left end sticks out
  try {
    Deformer d(s.mesh, moved);
    ADD_FAILURE() << "a mesh outside its cage was accepted";
  } catch (const MeshError& e) {
    EXPECT_EQ(e.code(), ErrorCode::MeshOutsideCage) << e.what();
    ASSERT_FALSE(e.findings().empty());
    EXPECT_EQ(e.findings()[0].code, "outside_cage");
  }
  Mesh flipped = s.mesh;  // one triangle against its neighbours (an open mesh is accepted: its holes are capped)
  std::swap(flipped.F(0, 1), flipped.F(0, 2));
  EXPECT_EQ(code_of([&] { Deformer d(flipped, s.cage); }), ErrorCode::InvalidMesh);
  MvcOptions cancel;
  cancel.progress = [](double) { return false; };
  const Scene big = test::capsule_scene({0, 0, 0}, 8, 20, 24);
  ASSERT_GT(big.mesh.V.rows(), 512);  // progress is reported every 256 rows
  EXPECT_EQ(code_of([&] { Deformer d(big.mesh, big.cage, cancel); }), ErrorCode::Cancelled);
  Deformer no_cage(s.mesh, Mesh{});
  const SolverOptions subspace = options_for(Method::Subspace, JacobianMode::Fast);
  EXPECT_EQ(code_of([&] { no_cage.set_options(subspace); }), ErrorCode::NoCage);
  EXPECT_EQ(code_of([&] { no_cage.set_handles({{0}, {}}); }), ErrorCode::InvalidArgument);
}

TEST(Deformer, StopCodesSayWhyACallReturned) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Deformer d(s.mesh, s.cage);
  EXPECT_EQ(d.step(0).stop, StopCode::NoIterations);
  const StepResult none = d.solve();
  EXPECT_EQ(none.stop, StopCode::NoHandles);
  EXPECT_TRUE(none.converged);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  const StepResult one = d.step(1);
  EXPECT_EQ(one.stop, StopCode::IterationLimit) << one.stop_reason;
  EXPECT_FALSE(one.converged);
  SolverOptions capped;
  capped.max_iterations = 1;
  d.set_options(capped);
  d.reset();
  EXPECT_EQ(d.solve().stop, StopCode::MaxIterations);
  for (Method method : {Method::Subspace, Method::Arap}) {
    d.set_options(options_for(method, JacobianMode::Fast));
    const StepResult r = d.solve();
    ASSERT_TRUE(r.converged) << r.stop_reason;
    EXPECT_TRUE(stop_code_converged(r.stop)) << stop_code_name(r.stop);
    if (method == Method::Arap) EXPECT_TRUE(r.stop == StopCode::ArapEnergy || r.stop == StopCode::StepTolerance);
    else EXPECT_NE(r.stop, StopCode::ArapEnergy);
  }
}

// Targets far beyond the mesh's scale: the line search may be unable to realise the decrease the model
// predicts. Then the solve must say so (stalled, not converged); a converged stop must be stationary; either
// way the volume is kept (the cubic's coefficients lose every digit at such sizes, so restoration is checked on
// the restored point itself). At 1e20 nothing can be resolved, so no mode may claim convergence.
TEST(Deformer, FarTargetsStallInsteadOfConverging) {
  for (double distance : {1e10, 1e20}) {
    for (const Combo& c : kCombos) {
      const Scene s = test::capsule_scene({distance, 0.0, 0.0});
      Deformer d(s.mesh, s.cage);
      d.set_options(options_for(c.method, c.mode));
      d.set_handles(s.groups);
      d.set_targets(s.targets);
      const StepResult r = d.solve();
      SCOPED_TRACE(std::string(c.name) + " at " + std::to_string(distance));
      ASSERT_FALSE(r.iterations.empty());
      const IterationStats& last = r.iterations.back();
      if (r.converged) {
        EXPECT_LT(distance, 1e20) << r.stop_reason;
        EXPECT_LE(-last.slope, 1e-6 * std::abs(last.merit_start)) << r.stop_reason;
      } else {
        EXPECT_TRUE(r.stop == StopCode::Stalled || r.stop == StopCode::NumericalFailure ||
                    r.stop == StopCode::MaxIterations)
            << stop_code_name(r.stop);
      }
      EXPECT_TRUE(d.positions().allFinite());
      for (const IterationStats& it : r.iterations) EXPECT_LE(std::abs(it.volume_rel_error), 1e-9);
    }
  }
}

// A user picks one vertex next to a fixed group (vertex 57 of the bar, 0.09 from vertices 0-2) and pulls it away.
// The subspace's first step is five times the model's size: restoring its volume cost more than the step gained,
// and the solve stopped "stalled" at rest (exact) or 0.32 short (fast). Both modes must make progress and reach
// the same minimum.
TEST(Deformer, APullNextToAFixedGroupMakesProgressInBothModes) {
  const Example bar = make_example("bar");
  Deformer d(bar.mesh, bar.cage);
  d.set_handles({{0, 1, 2}, {57}});
  Vertices targets(4, 3);
  for (int k = 0; k < 3; ++k) targets.row(k) = bar.mesh.V.row(k);
  targets.row(3) = bar.mesh.V.row(57) + Eigen::RowVector3d(0.3, -0.5, 0.0);
  std::vector<double> energies;
  std::vector<Vertices> shapes;
  for (JacobianMode mode : {JacobianMode::Exact, JacobianMode::Fast}) {
    d.set_options(options_for(Method::Subspace, mode));
    d.reset();
    d.set_targets(targets);
    const StepResult r = d.solve();
    SCOPED_TRACE(mode == JacobianMode::Exact ? "exact" : "fast");
    EXPECT_TRUE(r.converged) << r.stop_reason;
    for (size_t k = 1; k < r.iterations.size(); ++k)
      EXPECT_LE(r.iterations[k].merit, r.iterations[k - 1].merit * (1 + 1e-12)) << "iteration " << k;
    EXPECT_LE(std::abs(r.iterations.back().volume_rel_error), 1e-9);
    energies.push_back(r.iterations.back().energy);
    shapes.push_back(d.positions());
  }
  EXPECT_LT(energies[0], 0.6 * 0.17);  // 0.17: the energy at rest, where the exact mode stopped (the minimum: 0.087)
  EXPECT_NEAR(energies[0], energies[1], 1e-3 * energies[0]);
  EXPECT_LE(max_row_norm(Eigen::MatrixXd(shapes[0] - shapes[1])), 1e-3 * bbox(bar.mesh));
}

// Every converged stop is a stationary point of the Gauss-Newton model: its predicted decrease is a negligible
// fraction of the merit, however the stop was reached.
TEST(Deformer, ConvergedStopsAreStationary) {
  for (double distance : {0.5, 5.0, 50.0}) {
    const Scene s = test::capsule_scene({0.0, -distance, 0.0});
    Deformer d(s.mesh, s.cage);
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    const StepResult r = d.solve();
    SCOPED_TRACE(distance);
    if (!r.converged) continue;  // a stall or the cap is honest; what is checked is that "converged" is
    const IterationStats& last = r.iterations.back();
    EXPECT_LE(-last.slope, 1e-6 * std::abs(last.merit_start)) << r.stop_reason;
  }
}

// The trace a student steps through: every trial of the line search in order, alpha shrinking by c2, the
// accepted one the last and the only one restored, satisfying Armijo's condition against the recorded slope.
TEST(Deformer, IterationsRecordTheirLineSearch) {
  const Scene s = test::capsule_scene({0.0, -1.5, 0.5});
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  const SolverOptions o = d.options();
  const StepResult r = d.solve();
  ASSERT_TRUE(r.converged) << r.stop_reason;
  for (const IterationStats& it : r.iterations) {
    ASSERT_EQ(static_cast<int>(it.line_search.size()), it.line_search_trials);
    if (it.alpha == 0.0) continue;  // the record of a stop that did not move
    ASSERT_FALSE(it.line_search.empty());
    EXPECT_LT(it.slope, 0.0);
    EXPECT_GT(it.step_length, 0.0);
    for (size_t t = 0; t < it.line_search.size(); ++t) {
      const LineSearchTrial& trial = it.line_search[t];
      EXPECT_DOUBLE_EQ(trial.alpha, std::pow(o.armijo_c2, static_cast<double>(t)));
      EXPECT_EQ(trial.restored, t + 1 == it.line_search.size());
      if (trial.restored) {
        EXPECT_TRUE(trial.sufficient_decrease);
        EXPECT_LE(trial.merit, it.merit_start + o.armijo_c1 * trial.alpha * it.slope);
        EXPECT_EQ(trial.alpha, it.alpha);
      }
    }
    EXPECT_LE(it.merit, it.merit_start);
  }
}

// stepTolerance 0 is allowed; the line search still ends (steps below rounding noise are not tried).
TEST(Deformer, ZeroStepToleranceStillEnds) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Deformer d(s.mesh, s.cage);
  SolverOptions o;
  o.step_tolerance = 0.0;
  o.merit_tolerance = 0.0;
  o.max_iterations = 40;
  d.set_options(o);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  const StepResult r = d.solve();
  for (const IterationStats& it : r.iterations) EXPECT_LE(it.line_search_trials, 60);
  EXPECT_TRUE(d.positions().allFinite());
}

TEST(Deformer, SessionWithoutCageOffersFullSpaceAndArap) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Deformer d(s.mesh, Mesh{});
  EXPECT_EQ(d.options().method, Method::Full);
  EXPECT_EQ(d.cage_positions().rows(), 0);
  EXPECT_THROW(d.set_options(options_for(Method::Subspace, JacobianMode::Fast)), Error);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  const StepResult r = d.solve();
  EXPECT_TRUE(r.converged) << r.stop_reason;
}

// The session reports its cage's quality from its own W (the same numbers as the free function), and a
// session without a cage, or with the spectral basis, says it has none (code NoCage) instead of reporting anything.
TEST(Deformer, ReportsTheQualityOfItsCage) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Deformer d(s.mesh, s.cage);
  const CageQuality q = d.cage_quality();
  const CageQuality expected = cage_quality(d.basis(), s.mesh, s.cage);
  EXPECT_EQ(q.cage_vertices, static_cast<int>(s.cage.V.rows()));
  EXPECT_EQ(q.influence_ratio, expected.influence_ratio);
  EXPECT_EQ(q.volume_ratio, expected.volume_ratio);
  EXPECT_EQ(q.warnings, expected.warnings);
  Deformer none(s.mesh, Mesh{});
  try {
    none.cage_quality();
    ADD_FAILURE() << "a session without a cage reported a cage quality";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::NoCage);
  }
  // With the spectral basis W holds B, not cage coordinates: a cage kept beside it is not judged.
  BasisOptions spectral;
  spectral.kind = BasisKind::Spectral;
  spectral.spectral.modes = 8;
  Deformer with_spectral(s.mesh, s.cage, spectral);
  try {
    with_spectral.cage_quality();
    ADD_FAILURE() << "a session with the spectral basis reported a cage quality";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::NoCage);
  }
}

TEST(Deformer, ArapThroughTheSession) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  d.set_options(options_for(Method::Arap, JacobianMode::Fast));
  const StepResult r = d.step(30);
  ASSERT_FALSE(r.iterations.empty());
  EXPECT_TRUE(d.positions().allFinite());
  // Handles are hard constraints in ARAP.
  int row = 0;
  double worst = 0;
  for (const auto& g : s.groups)
    for (int v : g) worst = std::max(worst, (d.positions().row(v) - s.targets.row(row++)).norm());
  EXPECT_LE(worst, 1e-9 * bbox(s.mesh));
  EXPECT_EQ(d.cage_positions(), s.cage.V);  // the rest cage for non-subspace methods
}

// The step-through of ARAP: half steps on the session's positions, the same as a plain local-global iteration
// when put together; refused by the other methods and without handles.
TEST(Deformer, ArapHalfStepsMoveTheSessionAsOnePlainIteration) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0});
  Deformer halves(s.mesh, s.cage), whole(s.mesh, s.cage);
  EXPECT_THROW(halves.arap_half_step(true), Error);  // subspace method
  SolverOptions o = options_for(Method::Arap, JacobianMode::Fast);
  o.arap_acceleration = 0;
  halves.set_options(o);
  EXPECT_THROW(halves.arap_half_step(true), Error);  // no handles
  for (Deformer* d : {&halves, &whole}) {
    d->set_options(o);
    d->set_handles(s.groups);
    d->set_targets(s.targets);
  }
  const Vertices rest = halves.positions();
  const ArapHalfStep local = halves.arap_half_step(true);
  EXPECT_EQ(halves.positions(), rest);
  const ArapHalfStep global = halves.arap_half_step(false);
  EXPECT_LE(global.energy_after, global.energy_before);
  EXPECT_GT(global.step, 0.0);
  whole.step(1);
  EXPECT_LE((halves.positions() - whole.positions()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE(local.energy_after, local.energy_before + 1e-24);  // at rest both are 0 up to rounding
}

// ARAP's local-global iteration converges linearly with a long flat tail: before the relative-decrease
// rule the step tolerance (1e-7 x bbox) was never reached and every solve ran to the 100-iteration cap.
TEST(Deformer, ArapSolveStopsWhenTheEnergyStopsDecreasing) {
  // A finer capsule (~1000 vertices) than the other tests: its tail is long enough to show the problem.
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0}, 6, 30, 24, 8);
  Deformer d(s.mesh, s.cage);
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  SolverOptions o = options_for(Method::Arap, JacobianMode::Fast);
  o.arap_acceleration = 0;  // the plain local-global tail is what the rule is for
  d.set_options(o);
  const StepResult r = d.solve();
  ASSERT_TRUE(r.converged) << r.stop_reason;
  EXPECT_LE(static_cast<int>(r.iterations.size()), o.max_iterations / 2) << r.stop_reason;
  for (size_t k = 1; k < r.iterations.size(); ++k)  // local-global never raises the energy at fixed targets
    EXPECT_LE(r.iterations[k].energy, r.iterations[k - 1].energy * (1 + 1e-12)) << "iteration " << k + 1;
  const double stopped_at = r.iterations.back().energy;

  // The stop is near the minimum: a long run with the rule off lowers the energy by < 1e-3 relatively.
  o.arap_energy_tolerance = 0;
  o.max_iterations = 1500;
  Deformer reference(s.mesh, s.cage);
  reference.set_handles(s.groups);
  reference.set_targets(s.targets);
  reference.set_options(o);
  const StepResult long_run = reference.solve();
  const double minimum = long_run.iterations.back().energy;
  // The scene exercises the tail: the step tolerance alone (the old rule) needs more than the default cap.
  EXPECT_GT(static_cast<int>(long_run.iterations.size()), SolverOptions{}.max_iterations) << long_run.stop_reason;
  EXPECT_LE(minimum, stopped_at);
  EXPECT_LE(stopped_at - minimum, 1e-3 * minimum) << "stopped at " << stopped_at << ", long run " << minimum;

  // Iterating one step at a time (the app's loop) stops too, and the same targets re-sent keep the history.
  d.reset();
  bool converged = false;
  int calls = 0;
  while (!converged && calls < o.max_iterations) {
    d.set_targets(s.targets);
    converged = d.step(1).converged;
    ++calls;
  }
  EXPECT_TRUE(converged);
  EXPECT_EQ(calls, static_cast<int>(r.iterations.size()));
}

// Anderson acceleration (on by default) must end where plain local-global ends, never raise the energy at
// fixed targets, and get there in far fewer iterations.
TEST(Deformer, ArapAccelerationReachesTheSameMinimumFaster) {
  const Scene s = test::capsule_scene({0.0, -0.5, 0.0}, 6, 30, 24, 8);
  auto run = [&](int depth) {
    Deformer d(s.mesh, s.cage);
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    SolverOptions o = options_for(Method::Arap, JacobianMode::Fast);
    o.arap_acceleration = depth;
    o.arap_energy_tolerance = 0;  // stop on the step only: run both to the minimum
    o.step_tolerance = 1e-9;
    o.max_iterations = 3000;
    d.set_options(o);
    const StepResult r = d.solve();
    EXPECT_TRUE(r.converged) << "depth " << depth << ": " << r.stop_reason;
    for (size_t k = 1; k < r.iterations.size(); ++k)
      EXPECT_LE(r.iterations[k].energy, r.iterations[k - 1].energy * (1 + 1e-12))
          << "depth " << depth << ", iteration " << k + 1;
    return std::make_pair(r, Vertices(d.positions()));
  };
  const auto [plain, plain_x] = run(0);
  const auto [fast, fast_x] = run(5);
  std::cout << "[          ] ARAP to the minimum: " << plain.iterations.size() << " iterations plain, "
            << fast.iterations.size() << " with Anderson acceleration (depth 5)\n";
  EXPECT_NEAR(fast.iterations.back().energy, plain.iterations.back().energy, 1e-7 * plain.iterations.back().energy);
  EXPECT_LE(max_row_norm(Eigen::MatrixXd(fast_x - plain_x)), 1e-4 * bbox(s.mesh));
  EXPECT_LT(3 * fast.iterations.size(), plain.iterations.size());
}

TEST(Deformer, NoHandlesMeansNothingToSolve) {
  const Scene s = test::capsule_scene({0, 0, 0});
  Deformer d(s.mesh, s.cage);
  const StepResult r = d.solve();
  EXPECT_TRUE(r.converged);
  EXPECT_TRUE(r.iterations.empty());
  EXPECT_EQ(d.positions(), s.mesh.V);
}

TEST(Deformer, InvalidPairIsRejected) {
  Scene s = test::capsule_scene({0, 0, 0});
  s.cage.V.col(0).array() += 1.0;  // the bar sticks out of the cage
  EXPECT_THROW(Deformer(s.mesh, s.cage), Error);
}

TEST(Deformer, MemoryBudgetIsCheckedBeforeThePair) {
  // Both problems at once: the budget must be the one reported, since checking a large pair takes long
  // and an oversized W would be refused after it anyway.
  Scene s = test::capsule_scene({0, 0, 0});
  s.cage.V.col(0).array() += 1.0;  // the bar sticks out of the cage
  MvcOptions tiny;
  tiny.memory_budget_bytes = 1000;
  try {
    Deformer d(s.mesh, s.cage, tiny);
    FAIL() << "expected the budget error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("over the memory budget"), std::string::npos) << e.what();
  }
}

// A two-handle pull on a real model: the k vertices nearest the lowest point stay, the k nearest the
// highest point move sideways by 15% of the bounding-box diagonal.
void pull_real_model(const char* mesh_name, const char* cage_name) {
  SD_REQUIRE_SHARED_DATA(mesh_name);
  SD_REQUIRE_SHARED_DATA(cage_name);
  const Mesh mesh = test::load_shared_mesh(mesh_name);
  const Mesh cage = test::load_shared_mesh(cage_name);
  Deformer d(mesh, cage);
  const double diag = bbox(mesh);
  auto nearest = [&](Eigen::Index anchor, int k) {
    std::vector<std::pair<double, int>> dist;
    for (int i = 0; i < mesh.V.rows(); ++i) dist.push_back({(mesh.V.row(i) - mesh.V.row(anchor)).norm(), i});
    std::partial_sort(dist.begin(), dist.begin() + k, dist.end());
    std::vector<int> out;
    for (int i = 0; i < k; ++i) out.push_back(dist[i].second);
    return out;
  };
  Eigen::Index low, high;
  mesh.V.col(1).minCoeff(&low);
  mesh.V.col(1).maxCoeff(&high);
  const std::vector<std::vector<int>> groups = {nearest(low, 20), nearest(high, 20)};
  d.set_handles(groups);
  Vertices targets(40, 3);
  for (int k = 0; k < 40; ++k)
    targets.row(k) = mesh.V.row(groups[k / 20][k % 20]) +
                     (k >= 20 ? Eigen::RowVector3d(0.15 * diag, 0, 0) : Eigen::RowVector3d::Zero());
  d.set_targets(targets);
  for (JacobianMode mode : {JacobianMode::Fast, JacobianMode::Exact}) {
    d.set_options(options_for(Method::Subspace, mode));
    d.reset();
    const StepResult r = d.solve();
    EXPECT_TRUE(r.converged) << mesh_name << ": " << r.stop_reason;
    ASSERT_FALSE(r.iterations.empty());
    EXPECT_LE(std::abs(r.iterations.back().volume_rel_error), 1e-8);
    double ms = 0;
    int products = 0;
    for (const auto& it : r.iterations) {
      ms += it.ms;
      products += it.products;
    }
    std::cout << "[          ] " << mesh_name << " (" << mesh.V.rows() << " vertices) in " << cage_name << " ("
              << cage.V.rows() << "): " << (mode == JacobianMode::Fast ? "fast" : "exact") << " " << r.iterations.size()
              << " iterations, " << products << " products, energy " << r.iterations.front().energy << " -> "
              << r.iterations.back().energy << ", handle error "
              << std::sqrt(2 * r.iterations.back().position_energy / 40) / diag << " bbox (rms), " << ms << " ms, bind "
              << d.bind_ms() << " ms, precompute " << d.precompute_ms() << " ms; " << r.stop_reason << "\n";
  }
}

TEST(Deformer, ConvergesOnArmadillo) { pull_real_model("armadillo.obj", "armadillo_cage.obj"); }
TEST(Deformer, ConvergesOnGargoyle) { pull_real_model("gargoyle.obj", "gargoyle_cage_v67.obj"); }

}  // namespace
}  // namespace sd
