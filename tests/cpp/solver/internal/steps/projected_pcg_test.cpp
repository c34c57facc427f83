// Projected PCG against the dense KKT solution of the same equality-constrained quadratic program, on
// random symmetric positive definite systems of the shape the step solvers use (m by 3 blocks); and pcg_step's
// constraint curvature (pcg_step.h, length_curvature.h): added to A where it keeps the problem convex on the
// constraint, dropped where it does not.
#include "core/solver/internal/steps/projected_pcg.h"

#include <gtest/gtest.h>

#include <climits>
#include <random>

#include <Eigen/Dense>

#include "core/solver/internal/steps/pcg_step.h"

namespace sd {
namespace {

struct Qp {
  Eigen::MatrixXd A, M;  // 3m by 3m, on the flattened block (column-major: axis * m + row)
  Eigen::MatrixXd b, c;  // m by 3
  double g = 0;
};

Eigen::MatrixXd random_spd(int size, double condition, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd G(size, size);
  for (Eigen::Index i = 0; i < G.size(); ++i) G.data()[i] = normal(rng);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(G);
  const Eigen::MatrixXd Q = qr.householderQ();
  Eigen::VectorXd d(size);
  for (int i = 0; i < size; ++i) d[i] = std::pow(condition, double(i) / (size - 1));
  return Q * d.asDiagonal() * Q.transpose();
}

Qp random_qp(int m, double g, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Qp qp;
  qp.A = random_spd(3 * m, 1e4, rng);
  // A preconditioner close to A but not equal to it (as N is to W^T J^T J W).
  const Eigen::MatrixXd E = random_spd(3 * m, 10.0, rng);
  qp.M = qp.A + 0.3 * E;
  qp.b = Eigen::MatrixXd(m, 3);
  qp.c = Eigen::MatrixXd(m, 3);
  for (Eigen::Index i = 0; i < qp.b.size(); ++i) {
    qp.b.data()[i] = normal(rng);
    qp.c.data()[i] = normal(rng);
  }
  qp.g = g;
  return qp;
}

Eigen::VectorXd flat(const Eigen::MatrixXd& block) {
  return Eigen::Map<const Eigen::VectorXd>(block.data(), block.size());
}
Eigen::MatrixXd unflat(const Eigen::VectorXd& v, Eigen::Index m) {
  return Eigen::Map<const Eigen::MatrixXd>(v.data(), m, 3);
}

PcgOperator operator_of(const Qp& qp, int* products) {
  const Eigen::Index m = qp.b.rows();
  PcgOperator op;
  op.apply = [&qp, m, products](const Eigen::MatrixXd& P, Eigen::MatrixXd& AP, Eigen::MatrixXd& image) {
    AP = unflat(qp.A * flat(P), m);
    image = 2.0 * P;  // any linear map: the solver must carry it along as W h
    ++*products;
  };
  const Eigen::LLT<Eigen::MatrixXd> llt(qp.M);
  op.precondition = [llt, m](const Eigen::MatrixXd& R) {  // each m by 3 block of R
    Eigen::MatrixXd out(R.rows(), R.cols());
    for (Eigen::Index k = 0; k < R.cols() / 3; ++k)
      out.middleCols(3 * k, 3) = unflat(llt.solve(flat(R.middleCols(3 * k, 3))), m);
    return out;
  };
  return op;
}

// pcg_step's problem over `op`: its products (images of `rows` rows) and its preconditioner as the base.
PcgStepProblem step_problem(const PcgOperator& op, Eigen::Index rows) {
  PcgStepProblem problem;
  problem.product = [op](const Eigen::MatrixXd& V, Eigen::MatrixXd& image) {
    Eigen::MatrixXd AV;
    op.apply(V, AV, image);
    return AV;
  };
  problem.base_preconditioner = op.precondition;
  problem.image_rows = rows;
  return problem;
}

// Options for pcg_step that solve to rounding, without a memory.
SolverOptions tight_pcg_options() {
  SolverOptions options;
  options.cg_tolerance = 1e-12;
  options.cg_max_iterations = 500;
  options.cg_memory = 0;
  return options;
}

// The KKT system [A c; c^T 0] [h; lambda] = [-b; -g], solved densely.
std::pair<Eigen::MatrixXd, double> kkt_solution(const Qp& qp) {
  const Eigen::Index n = qp.A.rows();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + 1, n + 1);
  K.topLeftCorner(n, n) = qp.A;
  K.topRightCorner(n, 1) = flat(qp.c);
  K.bottomLeftCorner(1, n) = flat(qp.c).transpose();
  Eigen::VectorXd rhs(n + 1);
  rhs << -flat(qp.b), -qp.g;
  const Eigen::VectorXd x = K.fullPivLu().solve(rhs);
  return {unflat(x.head(n), qp.b.rows()), x[n]};
}

TEST(ProjectedPcg, ReachesTheKktSolutionAndStaysOnTheConstraint) {
  for (const double g : {0.0, 0.7}) {
    const Qp qp = random_qp(20, g, 11);
    int products = 0;
    ProjectedPcg pcg(operator_of(qp, &products), qp.b, qp.c, qp.g, qp.b.rows());
    pcg.run(1e-12, 500);
    const auto [h, lambda] = kkt_solution(qp);
    EXPECT_LE((pcg.h() - h).norm(), 1e-8 * h.norm()) << "g = " << g;
    EXPECT_NEAR(pcg.lambda()[0], lambda, 1e-8 * std::abs(lambda)) << "g = " << g;
    EXPECT_LE((pcg.image() - 2.0 * pcg.h()).norm(), 1e-12 * h.norm()) << "image is W h";
    EXPECT_EQ(pcg.products(), products);
    EXPECT_EQ(pcg.constraint_image_known(), g != 0.0) << "the start on c.h = -g costs one product";
  }
}

TEST(ProjectedPcg, EveryIterateIsFeasibleAndLowersTheQuadratic) {
  const Qp qp = random_qp(30, -0.4, 12);
  int products = 0;
  ProjectedPcg pcg(operator_of(qp, &products), qp.b, qp.c, qp.g, qp.b.rows());
  const auto quadratic = [&](const Eigen::MatrixXd& h) {
    return 0.5 * flat(h).dot(qp.A * flat(h)) + flat(qp.b).dot(flat(h));
  };
  double previous = quadratic(pcg.h());
  const double start = previous;
  for (int k = 1; k <= 15; ++k) {
    pcg.run(0.0, k + 1);  // one more product each time (the first was the start)
    EXPECT_NEAR(qp.c.cwiseProduct(pcg.h()).sum(), -qp.g, 1e-10) << "iteration " << k;
    const double q = quadratic(pcg.h());
    EXPECT_LE(q, previous + 1e-12 * std::abs(previous)) << "iteration " << k;  // (flat once converged)
    previous = q;
  }
  EXPECT_LT(previous, start - 1.0) << "the iteration made real progress";
}

// K constraints C^T h = -g (C: m by 3K): the KKT system [A C; C^T 0] [h; lambda] = [-b; -g].
TEST(ProjectedPcg, SeveralConstraintsReachTheKktSolution) {
  const int m = 20, K = 3;
  for (const bool start_on_constraints : {false, true}) {
    Qp qp = random_qp(m, 0.0, 15);
    std::mt19937 rng(16);
    std::normal_distribution<double> normal;
    Eigen::MatrixXd C(m, 3 * K);
    for (Eigen::Index i = 0; i < C.size(); ++i) C.data()[i] = normal(rng);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(K);
    if (start_on_constraints) g << 0.5, -0.3, 0.8;
    int products = 0;
    ProjectedPcg pcg(operator_of(qp, &products), qp.b, C, g, qp.b.rows());
    EXPECT_EQ(pcg.products(), start_on_constraints ? K : 0) << "the start on C^T h = -g costs one product each";
    pcg.run(1e-12, 500);
    const Eigen::Index n = qp.A.rows();
    Eigen::MatrixXd KKT = Eigen::MatrixXd::Zero(n + K, n + K);
    KKT.topLeftCorner(n, n) = qp.A;
    for (int k = 0; k < K; ++k) {
      KKT.block(0, n + k, n, 1) = flat(C.middleCols(3 * k, 3));
      KKT.block(n + k, 0, 1, n) = flat(C.middleCols(3 * k, 3)).transpose();
    }
    Eigen::VectorXd rhs(n + K);
    rhs << -flat(qp.b), -g;
    const Eigen::VectorXd x = KKT.fullPivLu().solve(rhs);
    EXPECT_LE((flat(pcg.h()) - x.head(n)).norm(), 1e-8 * x.head(n).norm());
    EXPECT_LE((pcg.lambda() - x.tail(K)).norm(), 1e-8 * x.tail(K).norm());
    for (int k = 0; k < K; ++k) EXPECT_NEAR(C.middleCols(3 * k, 3).cwiseProduct(pcg.h()).sum(), -g[k], 1e-10);
  }
}

TEST(ProjectedPcg, WithoutAConstraintItIsPlainPcg) {
  const Qp qp = random_qp(15, 0.0, 13);
  int products = 0;
  ProjectedPcg pcg(operator_of(qp, &products), qp.b, Eigen::MatrixXd(), 0.0, qp.b.rows());
  pcg.run(1e-12, 500);
  const Eigen::VectorXd h = -qp.A.llt().solve(flat(qp.b));
  EXPECT_LE((flat(pcg.h()) - h).norm(), 1e-8 * h.norm());
  EXPECT_EQ(pcg.lambda().size(), 0);
}

TEST(ProjectedPcg, StopsAtTheToleranceWithinTheBudget) {
  const Qp qp = random_qp(40, 0.0, 14);
  int products = 0;
  ProjectedPcg pcg(operator_of(qp, &products), qp.b, qp.c, 0.0, qp.b.rows());
  pcg.run(1e-2, 500);
  EXPECT_LE(pcg.relative_residual(), 1e-2);
  const int spent = pcg.products();
  pcg.run(1e-2, 500);  // already there: no more products
  EXPECT_EQ(pcg.products(), spent);
  pcg.run(1e-10, spent + 3);  // a budget caps the continuation
  EXPECT_EQ(pcg.products(), spent + 3);
  pcg.run_further(1e-10, 2);  // a budget beyond what was spent
  EXPECT_EQ(pcg.products(), spent + 5);
}

// cgMaxIterations may be INT_MAX: continuing by that many more products must not overflow the total (it wrapped to
// a negative budget, undefined behaviour that stopped the tighter solve at once), and reaches the tolerance.
TEST(ProjectedPcg, ContinuingByTheLargestBudgetDoesNotOverflow) {
  const Qp qp = random_qp(40, 0.0, 14);
  int products = 0;
  ProjectedPcg pcg(operator_of(qp, &products), qp.b, qp.c, 0.0, qp.b.rows());
  pcg.run(1e-2, INT_MAX);
  const int spent = pcg.products();
  ASSERT_GT(spent, 0);
  pcg.run_further(1e-8, INT_MAX);
  EXPECT_GT(pcg.products(), spent);
  EXPECT_LE(pcg.relative_residual(), 1e-8);
}

// pcg_step with a curvature term S added to every product: with a mild S (A + S positive definite) the step is the
// KKT solution of A + S; with one that makes A + S indefinite the run meets non-positive curvature, and the step is
// A's own, solved again, with both runs' products counted.
TEST(PcgStep, AddsTheCurvatureWhereItKeepsTheStepConvexAndDropsItWhereNot) {
  const Qp qp = random_qp(20, 0.7, 17);
  int products = 0;
  const PcgOperator op = operator_of(qp, &products);
  const PcgStepProblem problem = step_problem(op, qp.b.rows());
  SolverOptions options = tight_pcg_options();
  const Eigen::VectorXd g = Eigen::VectorXd::Constant(1, qp.g), scales = Eigen::VectorXd::Ones(1);
  const auto solve = [&](double shift) {
    PcgStepProblem curved = problem;
    if (shift != 0.0) curved.curvature = [shift](const Eigen::MatrixXd& V, Eigen::MatrixXd& AV) { AV += shift * V; };
    LbfgsPreconditioner memory;
    std::unique_ptr<ProjectedPcg> pcg;
    return pcg_step(curved, memory, qp.b, qp.c, g, scales, true, options, pcg);
  };
  const ConstrainedStep plain = solve(0.0);

  Qp shifted = qp;  // A's eigenvalues are 1 ... 1e4: A - 0.5 I stays positive definite
  shifted.A -= 0.5 * Eigen::MatrixXd::Identity(qp.A.rows(), qp.A.rows());
  const auto [h, lambda] = kkt_solution(shifted);
  const ConstrainedStep mild = solve(-0.5);
  EXPECT_LE((mild.du - h).norm(), 1e-8 * h.norm());
  EXPECT_NEAR(mild.lambda[0], lambda, 1e-8 * std::abs(lambda));
  EXPECT_GT((mild.du - plain.du).norm(), 1e-6 * h.norm()) << "the curvature changed the step";

  const ConstrainedStep strong = solve(-2e4);  // A + S negative definite
  EXPECT_LE((strong.du - plain.du).norm(), 1e-12 * plain.du.norm()) << "dropped: A's own step";
  // The indefinite run: its start on the constraint (one product) and the first direction, where it stopped.
  EXPECT_EQ(strong.products, plain.products + 2);
  EXPECT_LT(strong.slope, 0.0);

  // With an L-BFGS memory: the dropped run's products (of A + S) leave the memory as A's own run leaves it.
  options.cg_memory = 20;
  options.cg_tolerance = 1e-3;
  LbfgsPreconditioner plain_memory, strong_memory;
  std::unique_ptr<ProjectedPcg> pcg;
  pcg_step(problem, plain_memory, qp.b, qp.c, g, scales, true, options, pcg);
  PcgStepProblem curved = problem;
  int calls = 0;  // the first product (the start on the constraint) is convex and gives a pair; then indefinite
  curved.curvature = [&calls](const Eigen::MatrixXd& V, Eigen::MatrixXd& AV) { AV += (calls++ == 0 ? 1e3 : -2e4) * V; };
  pcg_step(curved, strong_memory, qp.b, qp.c, g, scales, true, options, pcg);
  ASSERT_EQ(calls, 2) << "the dropped run: one convex product, then the indefinite one";
  ASSERT_GT(plain_memory.size(), 0);
  EXPECT_EQ(strong_memory.size(), plain_memory.size());
  EXPECT_EQ(strong_memory.apply(qp.b, op.precondition), plain_memory.apply(qp.b, op.precondition));
}

// The first run's budget (the factor preconditioner's rent, gauss_newton_factor.h) counts the products beyond its
// start on the constraint; the run without the curvature, after an indefinite one, keeps the option's budget.
TEST(PcgStep, TheFirstRunsBudgetCountsBeyondItsStartAndTheRerunKeepsTheOptions) {
  const Qp qp = random_qp(20, 0.7, 17);
  int products = 0;
  const PcgStepProblem problem = step_problem(operator_of(qp, &products), qp.b.rows());
  const SolverOptions options = tight_pcg_options();
  const Eigen::VectorXd g = Eigen::VectorXd::Constant(1, qp.g), scales = Eigen::VectorXd::Ones(1);
  const auto solve = [&](const PcgStepProblem& p) {
    LbfgsPreconditioner memory;
    std::unique_ptr<ProjectedPcg> pcg;
    return pcg_step(p, memory, qp.b, qp.c, g, scales, true, options, pcg);
  };
  const ConstrainedStep plain = solve(problem);
  ASSERT_GT(plain.products, 6);
  PcgStepProblem budgeted = problem;
  budgeted.first_run_products = 3;
  const ConstrainedStep cut = solve(budgeted);
  EXPECT_EQ(cut.products, 1 + 3) << "the start on the constraint, then three";
  EXPECT_LT(cut.slope, 0.0);
  budgeted.first_run_products = 1000;  // above the option's: the option decides
  EXPECT_EQ(solve(budgeted).du, plain.du);

  budgeted.first_run_products = 3;
  budgeted.curvature = [](const Eigen::MatrixXd& V, Eigen::MatrixXd& AV) { AV -= 2e4 * V; };  // A + S indefinite
  const ConstrainedStep rerun = solve(budgeted);
  EXPECT_EQ(rerun.products, 2 + plain.products) << "the broken run (start, one direction), then A's whole run";
  EXPECT_LE((rerun.du - plain.du).norm(), 1e-12 * plain.du.norm());
}

}  // namespace
}  // namespace sd
