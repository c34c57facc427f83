// The skeleton constraint (core/skeleton/skeleton.h, solver/internal/constraints/skeleton_constraints.h): its checks,
// the points' coordinates (linear precision, partition of unity), finite-difference checks of the constraints'
// gradients, and the arm of issue 30 posed with and without bones in every method and integration: each bone's length
// to 1e-9 relative, the volume kept to 1e-9, the bones far straighter than without them (the middle held: its samples
// within 5e-2 of the length; without bones 9.5e-2 and 11% shorter).
#include "core/skeleton/skeleton.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/mesh/examples.h"
#include "core/mesh/shapes.h"
#include "core/mesh/volume.h"
#include "core/solver/deformer.h"
#include "core/basis/mean_value_coordinates.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/constraints/hard_constraints.h"
#include "core/solver/internal/constraints/length_curvature.h"
#include "core/solver/internal/constraints/restoring_directions.h"
#include "core/solver/internal/constraints/volume_restoration.h"
#include "core/solver/internal/constraints/skeleton_constraints.h"
#include "core/solver/internal/steps/subspace_step.h"
#include "skeleton/arm_scene.h"
#include "solver_fixtures.h"
#include "test_support.h"

namespace sd {
namespace {

using test::Arm;
using test::method;

// Posed arm: its skeleton report after a converged solve.
SkeletonReport pose(const Arm& arm, const SolverOptions& options, bool bones, double* volume_error = nullptr) {
  Deformer d(arm.mesh, arm.cage);
  d.set_options(options);
  d.set_handles(arm.groups);
  if (bones) d.set_skeleton(arm.skeleton);
  d.set_targets(arm.targets);
  const StepResult r = d.solve();
  // With bones Gauss-Newton converges only linearly (docs/method.md section 5.4): the fast steps may stop
  // "stalled" a few 1e-6 of the merit from the end, the full space's exact one at the cap; the subspace's converges.
  EXPECT_NE(r.stop, StopCode::NumericalFailure) << r.stop_reason;
  if ((options.jacobian == JacobianMode::Exact && options.method == Method::Subspace) || !bones)
    EXPECT_TRUE(r.converged) << r.stop_reason << " (method " << static_cast<int>(options.method) << ", jacobian "
                             << static_cast<int>(options.jacobian) << ", integration "
                             << static_cast<int>(options.integration) << ", " << r.iterations.size() << " iterations)";
  if (volume_error) *volume_error = std::abs(signed_volume(d.positions(), arm.mesh.F) / d.rest_volume() - 1.0);
  if (bones) return *d.skeleton_report();
  // Without bones: measure the same points (a skeleton only for its report, nothing solved with it).
  SkeletonConstraints measure(arm.skeleton, arm.mesh);
  return measure.report(measure.points(d.positions()));
}

TEST(Skeleton, ChecksNameTheProblem) {
  const Arm arm;
  Deformer d(arm.mesh, arm.cage);
  d.set_skeleton(arm.skeleton);
  auto rejects = [&](Skeleton s, const std::string& words) {
    try {
      d.set_skeleton(s);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::InvalidSkeleton);
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    EXPECT_EQ(d.skeleton().bones.size(), 2u) << "the old skeleton is kept";
  };
  Skeleton s = arm.skeleton;
  s.joints(2, 1) = 3.0;
  rejects(s, "outside the mesh");
  s = arm.skeleton;
  s.joints(1, 0) = std::nan("");
  rejects(s, "not a finite number");
  s = arm.skeleton;
  s.bones.push_back({2, 3});
  rejects(s, "outside [0, 3)");
  s.bones.back() = {1, 1};
  rejects(s, "to itself");
  s.bones.back() = {1, 0};
  rejects(s, "as an earlier bone does");
  s = arm.skeleton;
  s.joints(1, 0) = -2.0;
  rejects(s, "zero length");
  s = arm.skeleton;
  s.bones.pop_back();
  rejects(s, "ends no bone");
  s = arm.skeleton;
  s.bones.clear();
  rejects(s, "joints without bones");
  d.set_skeleton(Skeleton{});
  EXPECT_FALSE(d.skeleton_report().has_value());
}

// Two unit boxes (each [-0.5, 0.5]^3 before the shift), the second moved by `shift` along x.
Mesh two_boxes(double shift) {
  Mesh two = make_box(1.0, 1.0, 1.0, 1);
  const Eigen::Index n = two.V.rows();
  two.V.conservativeResize(2 * n, 3);
  two.V.bottomRows(n) = two.V.topRows(n).rowwise() + Eigen::RowVector3d(shift, 0, 0);
  const Eigen::Index f = two.F.rows();
  two.F.conservativeResize(2 * f, 3);
  two.F.bottomRows(f) = two.F.topRows(f).array() + static_cast<int>(n);
  return two;
}

Skeleton one_bone(const Eigen::RowVector3d& a, const Eigen::RowVector3d& c) {
  Skeleton s;
  s.joints.resize(2, 3);
  s.joints << a, c;
  s.bones = {{0, 1}};
  return s;
}

// Two joints inside two separate boxes: their bone crosses the air between them, where its points' coordinates would
// extrapolate (this used to reach the solver as "mesh vertices are outside the cage", naming no bone).
TEST(Skeleton, ABoneLeavingTheMeshBetweenItsJointsIsRefusedByName) {
  const Mesh two = two_boxes(2.0);
  Skeleton across = one_bone({0, 0, 0}, {2, 0, 0});
  test::expect_error([&] { validate_skeleton(across, two, true); }, "bone 0 (from joint 0 to joint 1) leaves the mesh",
                     ErrorCode::InvalidSkeleton);
  across.joints.row(1) << 0.3, 0.2, 0;  // within the first box: accepted
  validate_skeleton(across, two, true);
}

// A gap of 2% of the bone between two boxes, from 45% to 47% of its length: between its samples at 3/8 and 4/8,
// which are both inside (the check used to test only the samples, and accepted it). The segment is tested between
// its crossings of the surface, so the gap is found wherever it falls.
TEST(Skeleton, AThinGapBetweenTheBonesSamplesIsRefused) {
  const Mesh two = two_boxes(1.02);  // air for x in (0.5, 0.52)
  test::expect_error(
      [&] {
        validate_skeleton(one_bone({0.05, 0, 0}, {1.05, 0, 0}), two, true);
      },
      "bone 0 (from joint 0 to joint 1) leaves the mesh between its joints (at 46% of its length)",
      ErrorCode::InvalidSkeleton);
}

// Crossing a surface is not leaving the mesh: a bone from one part into another that overlaps it stays inside (the
// winding number is 1, then 2 in the overlap, then 1), and is accepted.
TEST(Skeleton, ABoneThroughOverlappingPartsIsAccepted) {
  const Mesh two = two_boxes(0.6);  // overlap for x in (0.1, 0.5)
  validate_skeleton(one_bone({-0.3, 0, 0}, {0.9, 0.1, 0}), two, true);
}

// In the full space only bones along each other make lengths dependent: the message names the bone and says so (it
// used to speak of too few cage vertices, which the full space does not use).
TEST(Skeleton, DependentLengthsInTheFullSpaceNameTheBoneAndTheCause) {
  const Arm arm;
  Deformer d(arm.mesh, arm.cage);
  d.set_options(method(Method::Full));
  Skeleton folded = arm.skeleton;
  folded.joints.row(2) = folded.joints.row(0);  // the second bone runs back along the first
  test::expect_error([&] { d.set_skeleton(folded); }, "bone 1's length is fixed by the bones before it",
                     ErrorCode::InvalidSkeleton);
  EXPECT_TRUE(d.skeleton().empty());
}

TEST(Skeleton, RefusedOnAnOpenMesh) {
  Mesh open = make_capsule(4.0, 0.5, 4, 16, 12);
  open.F.conservativeResize(open.F.rows() - 1, 3);  // one triangle less: a hole
  const Arm arm;
  Deformer d(open, arm.cage);
  try {
    d.set_skeleton(arm.skeleton);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidSkeleton);
    EXPECT_NE(std::string(e.what()).find("closed mesh"), std::string::npos) << e.what();
  }
}

TEST(Skeleton, PointsReproduceTheRestAndFollowAffineMaps) {
  const Arm arm;
  const SkeletonConstraints c(arm.skeleton, arm.mesh);
  const Eigen::MatrixXd& M = c.point_rows();
  ASSERT_EQ(M.cols(), 3 + SkeletonConstraints::kSamplesPerBone * 2);
  EXPECT_LE((M.colwise().sum().array() - 1.0).abs().maxCoeff(), 1e-12) << "partition of unity";
  const Eigen::MatrixXd rest = c.points(arm.mesh.V);
  EXPECT_LE((rest.topRows(3) - arm.skeleton.joints).cwiseAbs().maxCoeff(), 1e-10) << "linear precision";
  EXPECT_LE(c.values(rest).cwiseAbs().maxCoeff(), 1e-10) << "the rest pose meets every constraint";
  // An affine map of the mesh moves the points by the same map: a rotation keeps every constraint.
  Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Vertices X = (arm.mesh.V * R.transpose()).rowwise() + Eigen::RowVector3d(0.3, -1, 2);
  EXPECT_LE(c.values(c.points(X)).cwiseAbs().maxCoeff(), 1e-10);
}

// The subspace maps the points from its unknowns, q0 + (W^T m_q)^T (U - U0) (SubspaceStep::skeleton_points), not
// from the mesh: the same points as m_q^T X for X = X0 + W (U - U0), at rest and at any U; without U0 it declines.
// The rows W^T m_q are made once per skeleton and basis (SkeletonConstraints::rows_in).
TEST(Skeleton, TheSubspaceMapsThePointsFromItsUnknownsAsTheMeshDoes) {
  const Arm arm;
  DeformationEnergy energy(arm.mesh.V, arm.mesh.F);
  energy.set_skeleton(std::make_unique<SkeletonConstraints>(arm.skeleton, arm.mesh));
  const BasisMatrix W = mean_value_coordinates(arm.mesh.V, arm.cage);
  SubspaceStep step(energy, W);
  EXPECT_FALSE(step.skeleton_points(arm.cage.V).has_value()) << "no rest unknowns given: the energy maps them";
  step.set_rest_unknowns(arm.cage.V);
  const SkeletonConstraints& s = *energy.skeleton();
  for (double scale : {0.0, 0.3}) {
    const Eigen::MatrixXd U = arm.cage.V + scale * Eigen::MatrixXd::Random(arm.cage.V.rows(), 3);
    Eigen::MatrixXd image;
    W.multiply(U - arm.cage.V, image);
    const Vertices X = arm.mesh.V + image;
    const std::optional<Eigen::MatrixXd> mapped = step.skeleton_points(U);
    ASSERT_TRUE(mapped.has_value());
    EXPECT_LE((*mapped - s.points(X)).cwiseAbs().maxCoeff(), 1e-12) << "cage moved by " << scale;
  }
  // One W^T m_q per skeleton and basis: the step reads the rows the skeleton keeps (the session's check of what the
  // subspace can hold reads them too), equal to W^T m_q, and a basis of other rows is refused, not multiplied.
  const Eigen::MatrixXd& rows = s.rows_in(W);
  EXPECT_EQ(&step.skeleton_rows(), &rows) << "the step made its own copy";
  EXPECT_LE((rows - W.to_dense().transpose() * s.point_rows()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(&s.rows_in(W), &rows);
  EXPECT_THROW(s.rows_in(W.select_rows({0, 1, 2})), Error);
}

TEST(Skeleton, GradientsMatchFiniteDifferences) {
  const Arm arm;
  const SkeletonConstraints c(arm.skeleton, arm.mesh);
  const Vertices X = test::wobbled(arm.mesh, 0.1);
  const Eigen::MatrixXd G = c.gradients(c.points(X), c.point_rows());
  ASSERT_EQ(G.cols(), 3 * c.count());
  for (int k = 0; k < c.count(); ++k) {
    const Eigen::MatrixXd g = G.middleCols(3 * k, 3);
    const double error = test::gradient_error(X, g, [&](const Eigen::MatrixXd& Y) { return c.values(c.points(Y))[k]; });
    EXPECT_LE(error, 1e-6 * std::max(1e-3, g.cwiseAbs().maxCoeff())) << "constraint " << k;
  }
}

// The lengths' curvature (length_curvature.h) is sum_b lambda_b times the Hessian of bone b's length: central finite
// differences of the lengths' gradients along V, in X's space (rows m_q) with the volume's multiplier ahead of the
// bones' (which it must skip) and two blocks of V at once. Multipliers of another size or skeleton give none.
TEST(Skeleton, TheLengthsCurvatureIsTheirMultipliersTimesTheirHessians) {
  const Arm arm;
  DeformationEnergy energy(arm.mesh.V, arm.mesh.F);
  energy.set_skeleton(std::make_unique<SkeletonConstraints>(arm.skeleton, arm.mesh));
  const SkeletonConstraints& s = *energy.skeleton();
  const HardConstraints hard(energy, true);
  ASSERT_EQ(hard.volume_count(), 1);
  const Vertices X = test::wobbled(arm.mesh, 0.3);
  const EnergyEvaluation e = energy.evaluate(X);
  Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(hard.count(), -0.7, 0.9);
  LastMultipliers last;
  last.keep(lambda, energy.skeleton_version());
  const LengthCurvature curvature(hard, e, s.point_rows(), last);
  ASSERT_FALSE(curvature.empty());
  const Eigen::MatrixXd V = test::fixed_directions(X.rows(), 6);
  Eigen::MatrixXd AV = Eigen::MatrixXd::Zero(V.rows(), V.cols());
  curvature.add_times(V, AV);
  const double h = 1e-5;
  for (Eigen::Index t = 0; t < 2; ++t) {
    const Eigen::MatrixXd v = V.middleCols(3 * t, 3);
    const auto lengths_gradient = [&](const Vertices& Y) {
      const Eigen::MatrixXd G = s.gradients(s.points(Y), s.point_rows());
      Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(Y.rows(), 3);
      for (int b = 0; b < s.bone_count(); ++b) sum += lambda[hard.volume_count() + b] * G.middleCols(3 * b, 3);
      return sum;
    };
    const Eigen::MatrixXd fd = (lengths_gradient(X + h * v) - lengths_gradient(X - h * v)) / (2 * h);
    EXPECT_LE((AV.middleCols(3 * t, 3) - fd).norm(), 1e-6 * fd.norm()) << "block " << t;
    EXPECT_GT(fd.norm(), 1e-4) << "block " << t << ": not a trivial comparison";
  }
  last.keep(lambda.head(2), energy.skeleton_version());
  EXPECT_TRUE(LengthCurvature(hard, e, s.point_rows(), last).empty()) << "another set of constraints'";
  last.keep(lambda, energy.skeleton_version() - 1);
  EXPECT_TRUE(LengthCurvature(hard, e, s.point_rows(), last).empty()) << "another skeleton's, with as many bones";
  EXPECT_TRUE(LengthCurvature(hard, e, s.point_rows(), LastMultipliers()).empty());
}

// With the lengths' curvature the fast subspace steps converge in tens of iterations, not 130 (docs/method.md section
// 5.4), and the full integration's reaches the exact steps' minimiser (which factors A without the curvature); the
// full space's fast step takes it too.
TEST(Skeleton, WithTheLengthsCurvatureTheArmConvergesInFewIterations) {
  const Arm arm;
  const auto solve = [&](const SolverOptions& options) {
    Deformer d(arm.mesh, arm.cage);
    d.set_options(options);
    d.set_handles(arm.groups);
    d.set_skeleton(arm.skeleton);
    d.set_targets(arm.targets);
    return d.solve();
  };
  const StepResult exact = solve(method(Method::Subspace, JacobianMode::Exact));
  ASSERT_TRUE(exact.converged) << exact.stop_reason;
  for (const Integration integration : {Integration::Full, Integration::Reduced}) {
    const StepResult fast = solve(method(Method::Subspace, JacobianMode::Fast, integration));
    const std::string name = integration == Integration::Full ? "full" : "reduced";
    EXPECT_TRUE(fast.converged) << name << ": " << fast.stop_reason;
    EXPECT_LE(fast.iterations.size(), 40u) << name << " (132 and 131 without the curvature)";
    EXPECT_LE(fast.iterations.back().bone_length_error, 1e-9) << name;
    if (integration == Integration::Full)
      EXPECT_NEAR(fast.iterations.back().merit, exact.iterations.back().merit, 1e-9 * exact.iterations.back().merit);
  }
  const StepResult full = solve(method(Method::Full));
  EXPECT_TRUE(full.converged) << full.stop_reason;
  // 24 or 25 (the rounding of the restoration's Newton steps decides), 28 without the curvature.
  EXPECT_LE(full.iterations.size(), 25u) << "the full space";
  EXPECT_LE(full.iterations.back().bone_length_error, 1e-9);
}

// Restoration along the nonlinear constraints alone (restoring_directions.h): the combinations move each volume or
// length by one to first order and the linear middles by exactly zero, so a trial that holds the middles keeps them
// to rounding while its volume and lengths are restored. They are made only for directions kept from the last
// iteration, not for a trial that breaks the middles, and remade for a new skeleton even where the directions stay.
TEST(Skeleton, RestoringTheVolumeAndLengthsAloneKeepsTheMiddlesExactly) {
  const Arm arm;
  DeformationEnergy energy(arm.mesh.V, arm.mesh.F);
  energy.set_skeleton(std::make_unique<SkeletonConstraints>(arm.skeleton, arm.mesh));
  const HardConstraints hard(energy, true);
  ASSERT_EQ(hard.count(), 9);
  EXPECT_EQ(hard.nonlinear(), (std::vector<int>{0, 1, 2})) << "the volume and the two lengths";
  // The step's own directions: the constraints' gradients (any with invertible slopes restore).
  const Vertices& X0 = arm.mesh.V;
  const Eigen::MatrixXd G = hard.gradients(X0);
  const auto directions = [&](const SkeletonConstraints& s) {
    return RestoringDirections{G, std::make_shared<const Eigen::MatrixXd>(G), s.point_rows().transpose() * G, {}};
  };
  const RestoringDirections all = directions(*energy.skeleton());
  const Eigen::MatrixXd points = energy.skeleton()->points(X0);
  const Eigen::VectorXd at_rest = hard.values(X0);
  NonlinearRestoration made;
  made.next_step(all);
  EXPECT_EQ(made.for_trial(hard, all, X0, points, at_rest), nullptr) << "directions new this iteration";
  made.next_step(all);
  const RestoringDirections* nonlinear = made.for_trial(hard, all, X0, points, at_rest);
  ASSERT_NE(nonlinear, nullptr);
  ASSERT_EQ(nonlinear->dx->cols(), 9) << "three directions, not nine";
  const auto slopes = [&](const RestoringDirections& r) {
    return HardConstraints::Along(hard, X0, *r.dx).slopes(Eigen::Vector3d::Zero());
  };
  EXPECT_LE((slopes(*nonlinear).topRows(3) - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE(slopes(*nonlinear).bottomRows(6).cwiseAbs().maxCoeff(), 1e-12) << "the middles do not move";
  EXPECT_EQ(made.for_trial(hard, all, X0, points, at_rest), nonlinear) << "kept while the step's are";

  // A trial that bends the arm moves its middles too: not served. Put every constraint back along the step's own
  // directions, then stretch along x (lengths and volume change, the middles stay): served, and restored exactly.
  Vertices X = X0;
  for (Eigen::Index i = 0; i < X.rows(); ++i) X(i, 1) += 0.05 * X(i, 0) * X(i, 0) + 0.02 * X(i, 0);
  Eigen::MatrixXd U = X;
  EXPECT_GE(hard.relative_error(hard.values(X), {0, 1, 2}), 1e-3) << "volume and lengths broken";
  EXPECT_EQ(made.for_trial(hard, all, X0, points, hard.values(X)), nullptr) << "the bend moved the middles too";
  restore_constraints(hard, energy, X, U, all, 8);
  for (Eigen::Index i = 0; i < X.rows(); ++i) X(i, 0) *= 1.01;
  const Eigen::VectorXd stretched = hard.values(X);
  ASSERT_EQ(made.for_trial(hard, all, X0, points, stretched), nonlinear);
  EXPECT_GE(hard.relative_error(stretched), 5e-3);
  U = X;
  EXPECT_LE(restore_constraints(hard, energy, X, U, *nonlinear, 8), 1e-13);
  EXPECT_LE(hard.relative_error(hard.values(X)), 1e-13) << "volume, lengths and middles";
  // A constraint that is not a number is as far from holding as can be, whichever entry it is (not dropped by max).
  for (Eigen::Index k : {0, 4, 8}) {
    Eigen::VectorXd broken = hard.values(X);
    broken[k] = std::nan("");
    EXPECT_EQ(hard.relative_error(broken), std::numeric_limits<double>::infinity()) << "entry " << k;
    EXPECT_EQ(hard.relative_error(broken, {static_cast<int>(k)}), std::numeric_limits<double>::infinity());
  }

  // Another skeleton with as many constraints, the step's directions kept: the combinations are remade for its
  // middles (stale ones would move them).
  Skeleton moved = arm.skeleton;
  moved.joints(1, 0) = 0.6;
  energy.set_skeleton(std::make_unique<SkeletonConstraints>(moved, arm.mesh));
  const HardConstraints other(energy, true);
  ASSERT_EQ(other.nonlinear(), hard.nonlinear());
  const RestoringDirections same{all.du, all.dx, energy.skeleton()->point_rows().transpose() * G, {}};
  made.next_step(same);
  const RestoringDirections* remade = made.for_trial(other, same, X0, energy.skeleton()->points(X0), other.values(X0));
  ASSERT_NE(remade, nullptr);
  const Eigen::MatrixXd new_slopes = HardConstraints::Along(other, X0, *remade->dx).slopes(Eigen::Vector3d::Zero());
  EXPECT_LE(new_slopes.bottomRows(6).cwiseAbs().maxCoeff(), 1e-12) << "the new middles do not move";
}

TEST(Skeleton, TheArmBendsAtItsJointOnlyInEveryMethod) {
  const Arm arm;
  const SkeletonReport free = pose(arm, method(Method::Subspace), false);
  // Without bones the limbs shorten and sag (issue 30 measured 11% and 9.5%).
  EXPECT_GE(free.max_length_error(), 0.05);
  EXPECT_GE(free.max_straightness_error(), 0.05);
  const SolverOptions cases[] = {method(Method::Subspace), method(Method::Subspace, JacobianMode::Exact),
                                 method(Method::Subspace, JacobianMode::Fast, Integration::Reduced),
                                 method(Method::Full), method(Method::Full, JacobianMode::Exact)};
  for (const SolverOptions& o : cases) {
    double volume_error = 1;
    const SkeletonReport r = pose(arm, o, true, &volume_error);
    const std::string name = std::string(o.method == Method::Full ? "full" : "subspace") +
                             (o.jacobian == JacobianMode::Exact ? " exact" : " fast") +
                             (o.integration == Integration::Reduced ? " reduced" : "");
    EXPECT_LE(r.max_length_error(), 1e-9) << name;
    EXPECT_LE(r.max_straightness_error(), 5e-2) << name;
    EXPECT_LE(r.max_straightness_error(), 0.5 * free.max_straightness_error()) << name;
    EXPECT_LE(volume_error, 1e-9) << name;
    for (const BoneReport& b : r.bones) EXPECT_TRUE(b.straight_hard) << name;
    // The elbow bends: the forearm's joint moved down.
    EXPECT_LE(r.joints(2, 1), -1.0) << name;
  }
}

// Many bones: the built-in bar with the lesson's handles (its left end held, its right end pulled by (-1.2, -2.2, 0))
// and a chain of `joints` joints along its axis, wavy when `wave` (so that the subspace holds fewer middles). Each
// bone adds a length and a held middle, hard constraints whose start costs the fast step a product each. The PCG cap
// (cgMaxIterations, 50) counts the iterations beyond that start: when it counted the start too, these steps made no
// CG iteration, moved ~1e-6 and read "converged" at the rest pose (energy 5.47, the handles 2.5 from their targets).
StepResult solve_chain(const SolverOptions& options, int joints, bool wave) {
  const Example bar = make_example("bar");
  Deformer d(bar.mesh, bar.cage);
  d.set_options(options);
  const std::vector<std::vector<int>> groups = {{0, 1, 2, 3, 4, 5}, {5038, 5039, 5040, 5041}};
  d.set_handles(groups);
  Skeleton chain;
  chain.joints.resize(joints, 3);
  for (int j = 0; j < joints; ++j)
    chain.joints.row(j) << -2.4 + 4.8 * j / (joints - 1), wave ? 0.1 * std::sin(j) : 0.0,
        wave ? 0.1 * std::cos(j) : 0.0;
  for (int j = 0; j + 1 < joints; ++j) chain.bones.push_back({j, j + 1});
  d.set_skeleton(chain);
  Vertices targets(10, 3);
  Eigen::Index r = 0;
  for (size_t g = 0; g < groups.size(); ++g)
    for (int v : groups[g])
      targets.row(r++) = bar.mesh.V.row(v) + (g == 1 ? Eigen::RowVector3d(-1.2, -2.2, 0) : Eigen::RowVector3d::Zero());
  d.set_targets(targets);
  const StepResult result = d.solve();
  EXPECT_LE(d.skeleton_report()->max_length_error(), 1e-9);
  return result;
}

TEST(Skeleton, AStartOnManyConstraintsLeavesTheFastStepItsIterations) {
  // The full space, 14 bones (57 constraints: the volume, 14 lengths, 14 middles of three rows): the fast step
  // converges where the exact one does (energy 0.151).
  const StepResult full = solve_chain(method(Method::Full), 15, false);
  EXPECT_TRUE(full.converged) << full.stop_reason;
  EXPECT_LE(full.iterations.back().energy, 0.16);
  // The subspace, 29 wavy bones (63 constraints in its 84 unknowns: 11 middles held): ten iterations go most of the way
  // (0.081).
  SolverOptions subspace = method(Method::Subspace);
  subspace.max_iterations = 10;
  EXPECT_LE(solve_chain(subspace, 30, true).iterations.back().energy, 0.2);
}

// A chain of 23 short bones (0.21 long in a bar 0.8 thick) on the axis, the full space: the restoration's Newton
// system mixes the volume's rows with the bones'; unscaled, its LU called the slopes singular, no trial could be
// restored and the solve stalled at rest (an attack on skeleton scenes). Its rows are now relative to each
// constraint's scale.
TEST(Skeleton, ALongChainOfShortBonesRestoresInTheFullSpace) {
  const StepResult r = solve_chain(method(Method::Full), 24, false);
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_GE(r.iterations.size(), 3u);
  EXPECT_LE(r.iterations.back().energy, 0.16);
}

TEST(Skeleton, RestPoseIsAFixedPointAndASkeletonSetLaterRestoresLengths) {
  const Arm arm;
  Deformer d(arm.mesh, arm.cage);
  d.set_handles(arm.groups);
  d.set_skeleton(arm.skeleton);
  d.solve();  // targets at rest
  EXPECT_LE((d.positions() - arm.mesh.V).cwiseAbs().maxCoeff(), 1e-12);
  // Pose without bones, then add them: the next solve restores the lengths from the bent pose.
  d.set_skeleton(Skeleton{});
  d.set_targets(arm.targets);
  d.solve();
  EXPECT_FALSE(d.skeleton_report().has_value());
  d.set_skeleton(arm.skeleton);
  EXPECT_GE(d.skeleton_report()->max_length_error(), 0.05);
  const StepResult r = d.solve();
  EXPECT_NE(r.stop, StopCode::NumericalFailure) << r.stop_reason;
  EXPECT_LE(d.skeleton_report()->max_length_error(), 1e-9);
  // The merit never rises, and every iteration reports the bones.
  for (size_t k = 1; k < r.iterations.size(); ++k) EXPECT_LE(r.iterations[k].merit, r.iterations[k - 1].merit + 1e-12);
  EXPECT_EQ(r.iterations.back().bone_lambda.size(), 2u);
  EXPECT_LE(r.iterations.back().bone_length_error, 1e-9);
}

// The constraints' rows scale differently with the model's units (the volume's gradient as length^2, the bones'
// not at all); the step's Schur complement is equilibrated, so the arm in millimetres or in kilometres is the same
// arm. Before, x1000 and x0.001 failed with "not positive definite" in both spaces.
// The constraints' rows scale differently with the model's units (the volume's gradient as length^2, the bones'
// not at all); the step's Schur complement is equilibrated, so the arm in millimetres or in kilometres is the same
// arm. Before, x1000 failed with "not positive definite" in both spaces. The elbow may turn about the line from
// shoulder to wrist at almost no cost (docs/method.md section 5.4), and each solve stops a little before the end
// of that valley (pose() above), so the energy (which scales as units^2) is compared, not the elbow's place.
TEST(Skeleton, TheArmInOtherUnitsIsTheSameArmScaled) {
  const Arm arm;
  for (const Method m : {Method::Subspace, Method::Full}) {
    double reference_energy = 0;
    for (const double units : {1.0, 1e-3, 1e3}) {
      Mesh mesh = arm.mesh, cage = arm.cage;
      mesh.V *= units;
      cage.V *= units;
      Skeleton skeleton = arm.skeleton;
      skeleton.joints *= units;
      Deformer d(mesh, cage);
      d.set_options(method(m));
      d.set_handles(arm.groups);
      d.set_skeleton(skeleton);
      d.set_targets(units * arm.targets);
      const StepResult r = d.solve();
      ASSERT_TRUE(r.converged) << r.stop_reason << " (method " << static_cast<int>(m) << ", units " << units << ")";
      EXPECT_LE(d.skeleton_report()->max_length_error(), 1e-9) << units;
      EXPECT_LE(std::abs(signed_volume(d.positions(), mesh.F) / d.rest_volume() - 1.0), 1e-9) << units;
      const double energy = r.iterations.back().energy / (units * units);
      if (units == 1.0) reference_energy = energy;
      EXPECT_NEAR(energy, reference_energy, 0.01 * reference_energy)
          << "method " << static_cast<int>(m) << ", units " << units;
    }
  }
}

TEST(Skeleton, WithoutVolumeTheBonesStillHold) {
  const Arm arm;
  SolverOptions o = method(Method::Subspace);
  o.volume = false;
  EXPECT_LE(pose(arm, o, true).max_length_error(), 1e-9);
}

// representable() keeps a bone's middle where the correlation matrix of the rows kept with it keeps its smallest
// eigenvalue above 1e-8, and finds that by growing a Cholesky factor. The definition itself, eigenvalues of every
// trial set, chooses the same: a wavy chain of 29 bones on the bar's 28-vertex cage, whose middles only partly fit.
TEST(Skeleton, TheMiddlesHeldAreThoseTheEigenvaluesChoose) {
  const Arm arm;
  Skeleton chain;
  const int joints = 30;
  chain.joints.resize(joints, 3);
  for (int j = 0; j < joints; ++j)
    chain.joints.row(j) << -2.4 + 4.8 * j / (joints - 1), 0.1 * std::sin(j), 0.1 * std::cos(j);
  for (int j = 0; j + 1 < joints; ++j) chain.bones.push_back({j, j + 1});
  const SkeletonConstraints constraints(chain, arm.mesh);
  const BasisMatrix W = mean_value_coordinates(arm.mesh.V, arm.cage);
  const Eigen::MatrixXd& rows = constraints.rows_in(W);
  const std::vector<int> held = constraints.representable(rows, true);
  // The reference: the gradients of the lengths and of each held middle at rest, in the subspace, normalised.
  const Eigen::MatrixXd rest = constraints.points(arm.mesh.V);
  auto gradient_rows = [&](int bone, int axis) {  // 3m: the row's gradient with respect to the subspace's unknowns
    const auto [a, e] = chain.bones[static_cast<size_t>(bone)];
    const int sample = joints + 7 * bone + 3;  // the middle (samples 1/8 .. 7/8, after the joints)
    Eigen::VectorXd c = Eigen::VectorXd::Zero(rest.rows());
    Eigen::RowVector3d d;
    if (axis < 0) {
      c[e] = 1, c[a] = -1;
      d = (rest.row(e) - rest.row(a)).normalized();
    } else {
      c[sample] = 1, c[a] = -0.5, c[e] = -0.5;
      d = Eigen::RowVector3d::Unit(axis);
    }
    const Eigen::VectorXd r = rows * c;
    Eigen::VectorXd g(3 * r.size());
    for (int k = 0; k < 3; ++k) g.segment(k * r.size(), r.size()) = d[k] * r;
    return Eigen::VectorXd(g.normalized());
  };
  std::vector<Eigen::VectorXd> kept;
  for (int b = 0; b < joints - 1; ++b) kept.push_back(gradient_rows(b, -1));
  auto smallest = [](const std::vector<Eigen::VectorXd>& set) {
    Eigen::MatrixXd M(set.front().size(), static_cast<Eigen::Index>(set.size()));
    for (size_t k = 0; k < set.size(); ++k) M.col(static_cast<Eigen::Index>(k)) = set[k];
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M.transpose() * M).eigenvalues()[0];
  };
  int held_count = 0;
  for (int b = 0; b < joints - 1; ++b) {
    std::vector<Eigen::VectorXd> trial = kept;
    for (int axis = 0; axis < 3; ++axis) trial.push_back(gradient_rows(b, axis));
    const bool fits = smallest(trial) > 1e-8;
    if (fits) kept = trial;
    EXPECT_EQ(held[static_cast<size_t>(b)], fits ? 1 : 0) << "bone " << b;
    held_count += held[static_cast<size_t>(b)];
  }
  EXPECT_GT(held_count, 0);
  EXPECT_LT(held_count, joints - 1) << "the cage cannot hold every middle: the case would not test the choice";
}

TEST(Skeleton, ACoarseCageKeepsTheLengthsAndSaysWhichBonesItCannotKeepStraight) {
  // Four bones along a line in an 8-vertex box cage (24 unknowns): not every bone's middle fits beside the lengths
  // (five such bones' lengths are already dependent: an invalid_skeleton error, checked below).
  Arm arm;
  arm.cage = make_box(6.0, 1.6, 1.6, 1);
  const int NJ = 5;
  Skeleton many;
  many.joints.resize(NJ, 3);
  for (int j = 0; j < NJ; ++j) many.joints.row(j) << -2.0 + 4.0 * j / (NJ - 1), 0.0, 0.0;
  for (int b = 0; b + 1 < NJ; ++b) many.bones.push_back({b, b + 1});
  Deformer d(arm.mesh, arm.cage);
  d.set_handles(arm.groups);
  d.set_skeleton(many);
  const SkeletonReport rest = *d.skeleton_report();
  int soft = 0;
  for (const BoneReport& b : rest.bones) soft += b.straight_hard ? 0 : 1;
  EXPECT_GE(soft, 1) << "a box cage cannot hold six bones' middles";
  Eigen::MatrixXd small = arm.targets;
  small.bottomRows(static_cast<Eigen::Index>(arm.groups[1].size())).rowwise() += Eigen::RowVector3d(0, -0.3, 0);
  small.bottomRows(static_cast<Eigen::Index>(arm.groups[1].size())).rowwise() -= Eigen::RowVector3d(-1.2, -2.2, 0);
  d.set_targets(small);
  const StepResult r = d.solve();
  EXPECT_NE(r.stop, StopCode::NumericalFailure) << r.stop_reason;
  EXPECT_LE(d.skeleton_report()->max_length_error(), 1e-9);
  Skeleton five;
  five.joints.resize(6, 3);
  for (int j = 0; j < 6; ++j) five.joints.row(j) << -2.0 + 0.8 * j, 0.0, 0.0;
  for (int b = 0; b < 5; ++b) five.bones.push_back({b, b + 1});
  try {
    d.set_skeleton(five);
    ADD_FAILURE() << "five collinear bones accepted in a box cage";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidSkeleton);
    EXPECT_NE(std::string(e.what()).find("cannot be kept independently"), std::string::npos) << e.what();
  }
  EXPECT_EQ(d.skeleton().bones.size(), 4u) << "the four-bone skeleton is kept";
}

// A change that fails after its checks (here: the subspace of a box cage cannot keep five collinear bones' lengths
// independently, which the full space can) leaves the session as it was: the method, the weighting and the handles'
// weight, and the next iterations bit for bit those of a twin session that never tried.
TEST(Skeleton, ARefusedMethodSwitchLeavesTheSessionAsItWas) {
  Arm arm;
  arm.cage = make_box(6.0, 1.6, 1.6, 1);
  Skeleton five;
  five.joints.resize(6, 3);
  for (int j = 0; j < 6; ++j) five.joints.row(j) << -2.0 + 0.8 * j, 0.0, 0.0;
  for (int b = 0; b < 5; ++b) five.bones.push_back({b, b + 1});
  auto session = [&](Deformer& d) {
    d.set_options(method(Method::Full));
    d.set_handles(arm.groups);
    d.set_skeleton(five);
    d.set_targets(arm.targets);
    d.set_handle_lines({HandleLine{}, HandleLine::along(Eigen::Vector3d(0, 0, 1))});  // the moving end's depth free
  };
  Deformer tried(arm.mesh, arm.cage), twin(arm.mesh, arm.cage);
  session(tried);
  session(twin);
  SolverOptions refused = method(Method::Subspace);
  refused.weighting = EnergyWeighting::Uniform;
  refused.position_weight = 3.0;
  try {
    tried.set_options(refused);
    ADD_FAILURE() << "the subspace of a box cage accepted five collinear bones";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidSkeleton) << e.what();
  }
  EXPECT_EQ(tried.options().method, Method::Full);
  EXPECT_EQ(tried.options().weighting, twin.options().weighting);
  EXPECT_EQ(tried.options().position_weight, 1.0);
  EXPECT_EQ(tried.handle_lines(), twin.handle_lines());
  tried.step(3);
  twin.step(3);
  EXPECT_EQ(tried.positions(), twin.positions()) << "the energy (its handles, lines and weights) is the twin's";
  EXPECT_EQ(tried.handle_distances(), twin.handle_distances());
  EXPECT_LE(tried.skeleton_report()->max_length_error(), 1e-9);
}

TEST(Skeleton, ArapIgnoresIt) {
  const Arm arm;
  Deformer d(arm.mesh, arm.cage);
  d.set_options(method(Method::Arap));
  d.set_handles(arm.groups);
  d.set_skeleton(arm.skeleton);
  d.set_targets(arm.targets);
  d.solve();
  const SkeletonReport report = *d.skeleton_report();
  EXPECT_GE(report.max_length_error(), 1e-3);  // measured, not kept
  // And the report says so: no bone claims a held middle or a multiplier (it did: held 1, straight, ARAP's lambda
  // the last Gauss-Newton solve's).
  EXPECT_FALSE(report.kept);
  for (const BoneReport& bone : report.bones) {
    EXPECT_EQ(bone.held_samples, 0);
    EXPECT_FALSE(bone.straight_hard);
    EXPECT_EQ(bone.lambda, 0.0);
  }
  d.set_options(method(Method::Subspace));
  d.solve();
  EXPECT_TRUE(d.skeleton_report()->kept);
  EXPECT_LE(d.skeleton_report()->max_length_error(), 1e-9);
}

// 26 bones on the bar's axis in the full space: the restoration's Newton system is singular in the step's metric (a
// singular value 1e-15 of the largest), so no trial was restored and the solve stalled at rest. Where the LU fails,
// restoration takes the least-squares correction of minimum norm (volume_restoration.cpp, SlopeSolver).
TEST(Skeleton, TwentySixShortBonesInARowRestoreInTheFullSpace) {
  const StepResult r = solve_chain(method(Method::Full), 27, false);
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_GE(r.iterations.size(), 3u);
  EXPECT_LE(r.iterations.back().energy, 0.16);
}

}  // namespace
}  // namespace sd
