// The constrained Gauss-Newton solver below the Deformer session: derivatives against finite
// differences, the step's algebra, and the properties of a converged solve (exact vs fast, subspace vs
// full space, merit monotonicity, volume).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/steps/full_space_step.h"
#include "core/solver/internal/gauss_newton.h"
#include "core/basis/mean_value_coordinates.h"
#include "core/solver/internal/steps/gauss_newton_factor.h"
#include "core/solver/internal/steps/subspace_step.h"
#include "core/mesh/volume.h"
#include "solver_fixtures.h"
#include "test_support.h"

namespace sd {
namespace {

using test::Scene;

// Everything one solve needs, built from a scene.
struct Problem {
  Scene scene;
  DeformationEnergy energy;
  BasisMatrix W;
  explicit Problem(Scene s, bool with_weights = true, EnergyWeighting weighting = EnergyWeighting::Area)
      : scene(std::move(s)), energy(scene.mesh.V, scene.mesh.F, weighting) {
    if (with_weights) W = mean_value_coordinates(scene.mesh.V, scene.cage);
    std::vector<int> sizes;
    for (const auto& g : scene.groups) sizes.push_back(static_cast<int>(g.size()));
    energy.set_handles(test::flat_handles(scene), sizes);
    energy.set_targets(scene.targets);
  }
  Vertices map(const Eigen::MatrixXd& P) const {
    Eigen::MatrixXd X;
    W.multiply(P, X);
    return X;
  }
};

SolverOptions tight(JacobianMode mode, bool volume = true) {
  SolverOptions o;
  o.jacobian = mode;
  o.volume = volume;
  o.step_tolerance = 1e-10;
  o.merit_tolerance = 1e-14;
  o.max_iterations = 200;
  return o;
}

StepResult solve(const DeformationEnergy& energy, StepSolver& steps, GaussNewtonState& state, const SolverOptions& o) {
  return gauss_newton(energy, steps, state, o.max_iterations, o, StopCode::MaxIterations);
}

// A deformed point to test derivatives at (not the rest pose, where f = 0 hides errors in J^T f).
Eigen::MatrixXd perturbed_cage(const Problem& p, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  Eigen::MatrixXd P = p.scene.cage.V;
  for (Eigen::Index i = 0; i < P.size(); ++i) P.data()[i] += u(rng);
  return P;
}

// f flattened: [3 * vertex + axis for the Laplacian rows; then 3 * handle + axis].
Eigen::VectorXd flat_residual(const EnergyEvaluation& e) {
  Eigen::VectorXd f(e.laplacian_residual.size() + e.position_residual.size());
  f << Eigen::Map<const Eigen::VectorXd>(e.laplacian_residual.data(), e.laplacian_residual.size()),
      Eigen::Map<const Eigen::VectorXd>(e.position_residual.data(), e.position_residual.size());
  return f;
}

TEST(DeformationEnergy, GradientMatchesFiniteDifferences) {
  for (EnergyWeighting weighting : {EnergyWeighting::Area, EnergyWeighting::Uniform}) {
    SCOPED_TRACE(weighting == EnergyWeighting::Area ? "area" : "uniform");
    Problem p(test::capsule_scene({0.3, -0.5, 0.2}), true, weighting);
    const Vertices X = p.map(perturbed_cage(p, 0.1, 1));
    const EnergyEvaluation e = p.energy.evaluate(X);
    const Eigen::MatrixXd g = p.energy.jacobian(X).gradient(e);
    const double h = 1e-6;
    double worst = 0;
    for (int i = 0; i < X.rows(); i += 7)
      for (int a = 0; a < 3; ++a) {
        Vertices Xp = X, Xm = X;
        Xp(i, a) += h;
        Xm(i, a) -= h;
        const double fd = (p.energy.evaluate(Xp).energy - p.energy.evaluate(Xm).energy) / (2 * h);
        worst = std::max(worst, std::abs(fd - g(i, a)));
      }
    EXPECT_LE(worst, 1e-6 * g.cwiseAbs().maxCoeff()) << "max |FD - J^T f|";
  }
}

TEST(DeformationEnergy, NormalProductIsJacobianTransposeJacobian) {
  for (EnergyWeighting weighting : {EnergyWeighting::Area, EnergyWeighting::Uniform}) {
    SCOPED_TRACE(weighting == EnergyWeighting::Area ? "area" : "uniform");
    // u.(J^T J v) = (J u).(J v), with J u and J v by central differences of f.
    Problem p(test::capsule_scene({0.0, -0.4, 0.0}), true, weighting);
    const Vertices X = p.map(perturbed_cage(p, 0.1, 2));
    const EnergyJacobian J = p.energy.jacobian(X);
    std::mt19937 rng(3);
    std::normal_distribution<double> normal;
    Eigen::MatrixXd U(X.rows(), 6);
    for (Eigen::Index i = 0; i < U.size(); ++i) U.data()[i] = normal(rng);
    const double h = 1e-6;
    auto directional = [&](const Eigen::MatrixXd& d) {
      const Vertices Xp = X + h * d, Xm = X - h * d;
      return Eigen::VectorXd((flat_residual(p.energy.evaluate(Xp)) - flat_residual(p.energy.evaluate(Xm))) / (2 * h));
    };
    const Eigen::VectorXd Ju = directional(U.leftCols(3)), Jv = directional(U.rightCols(3));
    const Eigen::MatrixXd JtJ = J.normal_product(U);  // both vectors in one batched call
    const double expected = Ju.dot(Jv);
    EXPECT_NEAR(block_dot(U.leftCols(3), JtJ.rightCols(3)), expected, 1e-6 * Ju.norm() * Jv.norm());
    EXPECT_NEAR(block_dot(U.rightCols(3), JtJ.leftCols(3)), expected, 1e-6 * Ju.norm() * Jv.norm());
    EXPECT_NEAR(block_dot(U.leftCols(3), JtJ.leftCols(3)), Ju.squaredNorm(), 1e-6 * Ju.squaredNorm());
  }
}

TEST(SubspaceStep, GradientMatchesFiniteDifferences) {
  for (EnergyWeighting weighting : {EnergyWeighting::Area, EnergyWeighting::Uniform}) {
    SCOPED_TRACE(weighting == EnergyWeighting::Area ? "area" : "uniform");
    Problem p(test::capsule_scene({0.2, -0.6, 0.1}), true, weighting);
    SubspaceStep sub(p.energy, p.W);
    sub.refactor(p.energy);
    const Eigen::MatrixXd P = perturbed_cage(p, 0.1, 4);
    const Vertices X = p.map(P);
    const Eigen::MatrixXd g = sub.gradient(p.energy.jacobian(X), p.energy.evaluate(X));
    ASSERT_EQ(g.rows(), P.rows());
    const double worst =
        test::gradient_error(P, g, [&](const Eigen::MatrixXd& Q) { return p.energy.evaluate(p.map(Q)).energy; });
    EXPECT_LE(worst, 1e-6 * g.cwiseAbs().maxCoeff()) << "max |FD - W^T J^T f|";
  }
}

// A full-integration PCG run is cut where the factor would fall due (gauss_newton_factor.h), and only where a factor
// can be made: not with the option 'constant', nor without rotation terms.
TEST(SubspaceStep, CutsARunOnlyWhereAFactorCanBeMade) {
  Problem p(test::capsule_scene({0.2, -0.6, 0.1}));
  SubspaceStep sub(p.energy, p.W);
  sub.refactor(p.energy);
  SolverOptions factor, constant;
  constant.preconditioner = Preconditioner::Constant;
  const int unlimited = std::numeric_limits<int>::max();
  EXPECT_EQ(sub.products_before_factor(factor), unlimited) << "no rotation terms: no factor";
  int exact_counts = 0;
  sub.set_rotation_terms([&](const Eigen::MatrixXd&) { return Eigen::MatrixXd(); },
                         [&](bool exact) {
                           exact_counts += exact;
                           return 100;
                         });
  const int cut = sub.products_before_factor(factor);
  EXPECT_LT(cut, unlimited);
  EXPECT_GT(cut, GaussNewtonFactor::kGoodProducts);
  EXPECT_EQ(exact_counts, 0) << "no debt yet: the upper bound, without looking for the stiff vertices";
  EXPECT_EQ(sub.products_before_factor(constant), unlimited);
}

TEST(SubspaceStep, DenseJacobianMatchesFiniteDifferences) {
  for (EnergyWeighting weighting : {EnergyWeighting::Area, EnergyWeighting::Uniform}) {
    SCOPED_TRACE(weighting == EnergyWeighting::Area ? "area" : "uniform");
    Problem p(test::capsule_scene({0.2, -0.6, 0.1}), true, weighting);
    SubspaceStep sub(p.energy, p.W);
    const Eigen::MatrixXd P = perturbed_cage(p, 0.1, 5);
    const Vertices X = p.map(P);
    const Eigen::MatrixXd JW = sub.dense_jacobian(p.energy.jacobian(X));
    const Eigen::Index m = P.rows();
    ASSERT_EQ(JW.cols(), 3 * m);
    const Eigen::MatrixXd fd = test::central_differences(
        P, [&](const Eigen::MatrixXd& Q) { return flat_residual(p.energy.evaluate(p.map(Q))); });
    EXPECT_LE((fd - JW).cwiseAbs().maxCoeff(), 1e-6 * JW.cwiseAbs().maxCoeff()) << "max |FD - J_f W| over all columns";
  }
}

TEST(SubspaceStep, MatrixFreeProductMatchesDenseNormalMatrix) {
  Problem p(test::capsule_scene({0.0, -0.5, 0.0}));
  SubspaceStep sub(p.energy, p.W);
  const Vertices X = p.map(perturbed_cage(p, 0.1, 6));
  const EnergyJacobian J = p.energy.jacobian(X);
  const Eigen::MatrixXd JW = sub.dense_jacobian(J);
  const Eigen::Index m = p.W.cols();
  Eigen::MatrixXd V = Eigen::MatrixXd::Random(m, 6), image;
  const Eigen::MatrixXd AV = sub.product(J, V, image);
  for (int t = 0; t < 2; ++t) {
    const Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(V.middleCols(3 * t, 3).eval().data(), 3 * m);
    const Eigen::VectorXd dense = JW.transpose() * (JW * v);
    const Eigen::VectorXd free = Eigen::Map<const Eigen::VectorXd>(AV.middleCols(3 * t, 3).eval().data(), 3 * m);
    EXPECT_LE((dense - free).norm(), 1e-10 * dense.norm()) << "system " << t;
  }
  EXPECT_LE((image - p.map(V.leftCols(3)).cast<double>()).leftCols(3).norm(), 1e-12 * image.norm());
}

TEST(SubspaceStep, StepSatisfiesLinearizedConstraintAndDescends) {
  for (JacobianMode mode : {JacobianMode::Exact, JacobianMode::Fast}) {
    Problem p(test::capsule_scene({0.0, -0.6, 0.0}));
    SubspaceStep sub(p.energy, p.W);
    sub.refactor(p.energy);
    const Eigen::MatrixXd P = perturbed_cage(p, 0.05, 7);  // off the volume constraint: g != 0
    const Vertices X = p.map(P);
    const EnergyEvaluation e = p.energy.evaluate(X);
    ASSERT_GT(std::abs(e.constraint[0]), 1e-4 * p.energy.rest_volume());
    const ConstrainedStep step = sub.compute(p.energy.jacobian(X), e, X, P, tight(mode));
    Eigen::MatrixXd c;
    p.W.multiply_transpose(p.energy.volume_gradient(X), c);
    // Linearized constraint g + c.h = 0 (the sign of lambda matters here).
    EXPECT_NEAR(block_dot(c, step.du), -e.constraint[0], 1e-8 * std::abs(e.constraint[0])) << static_cast<int>(mode);
    EXPECT_LT(step.slope, 0.0);
    // dx is W du.
    EXPECT_LE((Eigen::MatrixXd(p.map(step.du)) - step.dx).norm(), 1e-10 * step.dx.norm());
  }
}

TEST(SubspaceStep, StepSatisfiesEachPartsLinearizedConstraint) {
  for (JacobianMode mode : {JacobianMode::Exact, JacobianMode::Fast}) {
    Problem p(test::capsule_scene({0.0, -0.6, 0.0}));
    p.energy.set_volume_parts(test::capsule_thirds(p.scene.mesh));
    SubspaceStep sub(p.energy, p.W);
    sub.refactor(p.energy);
    const Eigen::MatrixXd P = perturbed_cage(p, 0.05, 7);
    const Vertices X = p.map(P);
    const EnergyEvaluation e = p.energy.evaluate(X);
    ASSERT_EQ(e.constraint.size(), 3);
    // (The fast step's projected PCG keeps every iterate on the constraints: its default tolerance is enough.)
    const ConstrainedStep step = sub.compute(p.energy.jacobian(X), e, X, P, tight(mode));
    Eigen::MatrixXd C;
    p.W.multiply_transpose(p.energy.constraint_gradients(X), C);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(block_dot(C.middleCols(3 * k, 3), step.du), -e.constraint[k],
                  1e-8 * e.constraint.cwiseAbs().maxCoeff())
          << "part " << k << (mode == JacobianMode::Exact ? " exact" : " fast");
    EXPECT_LT(step.slope, 0.0);
    EXPECT_EQ(step.lambda.size(), 3);
    ASSERT_TRUE(step.restore.dx);
    EXPECT_EQ(step.restore.dx->cols(), 9) << "one restoring direction per part";
  }
}

TEST(GaussNewton, RestoreVolumeReachesEveryPartsRestVolume) {
  Problem p(test::capsule_scene({0, 0, 0}));
  p.energy.set_volume_parts(test::capsule_thirds(p.scene.mesh));
  Vertices X = p.scene.mesh.V;
  for (Eigen::Index i = 0; i < X.rows(); ++i) X.row(i) *= 1.0 + 0.02 * std::sin(3.0 * X(i, 0));  // uneven change
  Eigen::MatrixXd U = X;
  const Eigen::MatrixXd R = p.energy.constraint_gradients(X);  // any directions with C^T R invertible
  ASSERT_GT(p.energy.constraints(X).cwiseAbs().maxCoeff(), 1e-3 * p.energy.rest_volume());
  const double left = restore_constraints(HardConstraints(p.energy, true), p.energy, X, U,
                                          {R, std::make_shared<const Eigen::MatrixXd>(R)}, 8);
  EXPECT_LE(std::abs(left), 1e-14);
  EXPECT_LE(p.energy.constraints(X).cwiseAbs().maxCoeff(), 1e-13 * p.energy.rest_volume());
  EXPECT_LE((U - Eigen::MatrixXd(X)).norm(), 1e-13 * X.norm()) << "U moves with X";
}

TEST(GaussNewton, RestoreVolumeReachesTheRestVolume) {
  Problem p(test::capsule_scene({0, 0, 0}));
  Vertices X = p.scene.mesh.V * 1.01;  // 3% more volume
  Eigen::MatrixXd U = X;
  const Eigen::MatrixXd r = p.energy.volume_gradient(X);
  const double left = restore_constraints(HardConstraints(p.energy, true), p.energy, X, U,
                                          {r, std::make_shared<const Eigen::MatrixXd>(r)});
  EXPECT_LE(std::abs(left), 1e-13);
  EXPECT_NEAR(signed_volume(X, p.scene.mesh.F), p.energy.rest_volume(), 1e-12 * p.energy.rest_volume());
  EXPECT_LE((U - Eigen::MatrixXd(X)).norm(), 1e-14 * X.norm());
}

// Solves the bend with both step modes from rest and checks convergence properties on the way.
struct Solved {
  StepResult result;
  GaussNewtonState state;
};

Solved solve_subspace(Problem& p, SubspaceStep& sub, const SolverOptions& o) {
  Solved s{{}, {p.scene.mesh.V, p.scene.cage.V, 0}};
  s.result = solve(p.energy, sub, s.state, o);
  return s;
}

void expect_merit_never_increases(const StepResult& r, const std::string& what) {
  for (size_t k = 1; k < r.iterations.size(); ++k)
    EXPECT_LE(r.iterations[k].merit, r.iterations[k - 1].merit * (1 + 1e-12) + 1e-300)
        << what << ": iteration " << r.iterations[k].iteration;
}

TEST(GaussNewton, ExactAndFastReachTheSameMinimizer) {
  Problem p(test::capsule_scene({0.2, -0.7, 0.1}));
  SubspaceStep sub(p.energy, p.W);
  sub.refactor(p.energy);
  const Solved exact = solve_subspace(p, sub, tight(JacobianMode::Exact));
  const Solved fast = solve_subspace(p, sub, tight(JacobianMode::Fast));
  ASSERT_TRUE(exact.result.converged) << exact.result.stop_reason;
  ASSERT_TRUE(fast.result.converged) << fast.result.stop_reason;
  const double e_exact = exact.result.iterations.back().energy, e_fast = fast.result.iterations.back().energy;
  EXPECT_NEAR(e_fast, e_exact, 1e-8 * e_exact);
  const double bbox = bounding_box_diagonal(p.scene.mesh.V);
  EXPECT_LE(max_row_norm(Eigen::MatrixXd(exact.state.X - fast.state.X)), 1e-5 * bbox);
  const double e_rest = p.energy.evaluate(p.scene.mesh.V).energy;
  for (const Solved* s : {&exact, &fast}) {
    expect_merit_never_increases(s->result, s == &exact ? "exact" : "fast");
    EXPECT_LE(std::abs(s->result.iterations.back().volume_rel_error), 1e-8);
    EXPECT_LT(s->result.iterations.back().energy, 0.5 * e_rest);
    for (const auto& it : s->result.iterations)
      std::cout << "[          ]   " << (s == &exact ? "exact" : "fast") << " " << it.iteration << " energy "
                << it.energy << " step " << it.step << " trials " << it.line_search_trials << " cg "
                << it.inner_iterations << " vol " << it.volume_rel_error << " lambda " << it.lambda << "\n";
  }
  std::cout << "[          ] bend, n = " << p.W.rows() << ", m = " << p.W.cols() << ": exact "
            << exact.result.iterations.size() << " iterations, fast " << fast.result.iterations.size()
            << " iterations, energy " << e_exact << " vs " << e_fast << "\n";
}

TEST(GaussNewton, VolumeOffLeavesTheVolumeFreeAndStillDescends) {
  // Squash: the right end pushed towards the left one.
  Problem p(test::capsule_scene({-0.6, 0.0, 0.0}));
  SubspaceStep sub(p.energy, p.W);
  sub.refactor(p.energy);
  const Solved on = solve_subspace(p, sub, tight(JacobianMode::Fast, true));
  const Solved off = solve_subspace(p, sub, tight(JacobianMode::Fast, false));
  ASSERT_TRUE(on.result.converged && off.result.converged);
  EXPECT_LE(std::abs(on.result.iterations.back().volume_rel_error), 1e-8);
  EXPECT_GE(std::abs(off.result.iterations.back().volume_rel_error), 1e-2) << "the squash should change the volume";
  for (const auto& it : off.result.iterations) EXPECT_EQ(it.lambda, 0.0);
  expect_merit_never_increases(off.result, "volume off");
  // The unconstrained minimum has less energy than the constrained one.
  EXPECT_LT(off.result.iterations.back().energy, on.result.iterations.back().energy);
}

TEST(GaussNewton, IdentitySubspaceAgreesWithFullSpace) {
  // W = I makes the subspace problem the full-space problem; both solvers must find the same point.
  Problem p(test::capsule_scene({0.0, -0.4, 0.2}, 3, 3, 10), false);
  const int n = static_cast<int>(p.scene.mesh.V.rows());
  p.W = BasisMatrix(n, n, false);
  for (int i = 0; i < n; ++i) p.W.set(i, i, 1.0);
  SubspaceStep sub(p.energy, p.W);
  sub.refactor(p.energy);
  FullSpaceStep full(p.energy);
  full.refactor(p.energy);
  for (JacobianMode mode : {JacobianMode::Exact, JacobianMode::Fast}) {
    const SolverOptions o = tight(mode);
    GaussNewtonState a{p.scene.mesh.V, p.scene.mesh.V, 0}, b{p.scene.mesh.V, p.scene.mesh.V, 0};
    // Compare the first steps exactly, then the minimizers.
    const EnergyEvaluation e = p.energy.evaluate(a.X);
    const EnergyJacobian J = p.energy.jacobian(a.X);
    const ConstrainedStep sa = sub.compute(J, e, a.X, a.U, o), sb = full.compute(J, e, b.X, b.U, o);
    EXPECT_LE((sa.dx - sb.dx).norm(), (mode == JacobianMode::Exact ? 1e-6 : 1e-8) * sb.dx.norm());
    EXPECT_NEAR(sa.lambda[0], sb.lambda[0], 1e-6 * std::abs(sb.lambda[0]) + 1e-12);
    const StepResult ra = solve(p.energy, sub, a, o), rb = solve(p.energy, full, b, o);
    EXPECT_NEAR(ra.iterations.back().energy, rb.iterations.back().energy, 1e-7 * rb.iterations.back().energy);
    EXPECT_LE(max_row_norm(Eigen::MatrixXd(a.X - b.X)), 1e-5 * bounding_box_diagonal(p.scene.mesh.V));
    expect_merit_never_increases(rb, "full space");
  }
}

TEST(GaussNewton, FullSpaceExactAndFastAgree) {
  Problem p(test::capsule_scene({0.1, -0.5, 0.0}), false);
  FullSpaceStep full(p.energy);
  full.refactor(p.energy);
  SolverOptions fast = tight(JacobianMode::Fast);
  fast.cg_max_iterations = 500;
  GaussNewtonState a{p.scene.mesh.V, p.scene.mesh.V, 0}, b = a;
  const StepResult ra = solve(p.energy, full, a, tight(JacobianMode::Exact));
  const StepResult rb = solve(p.energy, full, b, fast);
  EXPECT_TRUE(ra.converged) << ra.stop_reason;
  EXPECT_TRUE(rb.converged) << rb.stop_reason;
  EXPECT_NEAR(ra.iterations.back().energy, rb.iterations.back().energy, 1e-6 * ra.iterations.back().energy);
  EXPECT_LE(std::abs(ra.iterations.back().volume_rel_error), 1e-8);
  std::cout << "[          ] full space: exact " << ra.iterations.size() << " iterations, fast " << rb.iterations.size()
            << " iterations\n";
}

TEST(GaussNewton, RestPoseIsAFixedPoint) {
  Problem p(test::capsule_scene({0, 0, 0}));
  SubspaceStep sub(p.energy, p.W);
  sub.refactor(p.energy);
  for (JacobianMode mode : {JacobianMode::Exact, JacobianMode::Fast}) {
    GaussNewtonState s{p.scene.mesh.V, p.scene.cage.V, 0};
    const StepResult r = solve(p.energy, sub, s, tight(mode));
    EXPECT_TRUE(r.converged) << r.stop_reason;
    EXPECT_LE(max_row_norm(Eigen::MatrixXd(s.X - p.scene.mesh.V)), 1e-10 * bounding_box_diagonal(p.scene.mesh.V));
  }
}

// An interactive frame: the targets move, X does not. The next call reuses the evaluation the last one left
// (updating only the handle terms) instead of evaluating the whole mesh again; the iterates must be the ones a
// fresh evaluation gives.
TEST(GaussNewton, CarriedOverEvaluationGivesTheSameStepAsAFreshOne) {
  Problem p(test::capsule_scene({0.2, -0.3, 0.1}));
  SubspaceStep carried(p.energy, p.W), fresh(p.energy, p.W);
  carried.refactor(p.energy);
  fresh.refactor(p.energy);
  const SolverOptions o = tight(JacobianMode::Fast);
  GaussNewtonState a{p.scene.mesh.V, p.scene.cage.V, 0}, b = a;
  gauss_newton(p.energy, carried, a, 2, o, StopCode::IterationLimit);
  gauss_newton(p.energy, fresh, b, 2, o,
               StopCode::IterationLimit);  // the same two iterations: both step solvers have one history
  ASSERT_TRUE(a.evaluation.has_value());
  Vertices moved = p.energy.targets();
  moved.col(1).array() += 0.05;
  p.energy.set_targets(moved);
  b.evaluation.reset();
  const StepResult ra = gauss_newton(p.energy, carried, a, 1, o, StopCode::IterationLimit);
  const StepResult rb = gauss_newton(p.energy, fresh, b, 1, o, StopCode::IterationLimit);
  ASSERT_EQ(ra.iterations.size(), 1u);
  ASSERT_EQ(rb.iterations.size(), 1u);
  EXPECT_EQ(ra.iterations[0].energy, rb.iterations[0].energy);
  EXPECT_LE(max_row_norm(Eigen::MatrixXd(a.X - b.X)), 1e-14 * bounding_box_diagonal(p.scene.mesh.V));
  // The evaluation carried forward is the one at the new X with the new targets.
  const EnergyEvaluation now = p.energy.evaluate(a.X);
  EXPECT_NEAR(a.evaluation->energy, now.energy, 1e-14 * now.energy);
  EXPECT_NEAR(a.evaluation->volume, now.volume, 1e-14 * std::abs(now.volume));
}

}  // namespace
}  // namespace sd
