// The solver's results do not depend on the number of threads: the same scene solved with 1, 2, 4 and 16 threads
// (more than most machines running the tests have cores: the threads then take turns, which must not matter) gives
// bit-identical weights, positions, energies, iteration counts and stop reasons in every method and mode, with a
// skeleton and its straightness term too, and through a reduced solve's finishing iterations (every parallel kernel
// uses the fixed blocks of cpp/core/parallel/parallel_for.h).
#include "core/solver/deformer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "core/parallel/thread_pool.h"
#include "core/skeleton/skeleton.h"
#include "solver_fixtures.h"

namespace sd {
namespace {

struct SolveRecord {
  Eigen::MatrixXd weights;
  Vertices positions;
  std::vector<double> energies;
  std::vector<int> products;
  std::string stop_reason;
  bool finished = false;  // a reduced solve that reached its finishing iterations
};

bool bit_identical(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

// A capsule of about 4000 vertices, so that every kernel's range spans several blocks.
const test::Scene& scene() {
  static const test::Scene s = test::capsule_scene({0.0, -0.7, 0.2}, 8, 60, 48, 8);
  return s;
}

struct Case {
  Method method;
  JacobianMode mode;
  const char* name;
  Integration integration = Integration::Full;
  Preconditioner preconditioner = Preconditioner::Constant;
  bool bones = false;
  int max_iterations = 5;  // a reduced solve needs more to reach its finishing iterations (method.md 17.3)
};

SolveRecord solve_with(int threads, const Case& c) {
  EXPECT_EQ(parallel::set_threads(threads), threads);
  const test::Scene& s = scene();
  Deformer d(s.mesh, s.cage);
  SolverOptions o;
  o.method = c.method;
  o.jacobian = c.mode;
  o.integration = c.integration;
  o.preconditioner = c.preconditioner;
  // The capsule is easy for N (about 3 products): a tight tolerance makes runs long enough to make the factor.
  if (c.preconditioner == Preconditioner::GaussNewton) o.cg_tolerance = 1e-4;
  // The exact full-space step (a sparse LDLT of 3n x 3n per iteration) is the slow one: two iterations.
  o.max_iterations = c.method == Method::Full && c.mode == JacobianMode::Exact ? 2 : c.max_iterations;
  const bool bones = c.bones;
  if (bones) o.straightness_weight = 3.0;
  d.set_options(o);
  d.set_handles(s.groups);
  if (bones) {  // two bones along the capsule's axis (x from -1.4 to 1.4)
    Skeleton skeleton;
    skeleton.joints.resize(3, 3);
    skeleton.joints << -0.9, 0, 0, 0, 0, 0, 0.9, 0, 0;
    skeleton.bones = {{0, 1}, {1, 2}};
    d.set_skeleton(skeleton);
  }
  d.set_targets(s.targets);
  const StepResult r = d.solve();
  SolveRecord run;
  if (c.method == Method::Subspace) run.weights = d.basis().to_dense();
  run.positions = d.positions();
  for (const IterationStats& it : r.iterations) {
    run.energies.push_back(it.energy);
    run.products.push_back(it.products);
  }
  run.finished = !r.iterations.empty() && r.iterations.back().finishing;
  run.stop_reason = r.stop_reason;
  return run;
}

TEST(DeformerThreads, OneTwoFourAndSixteenThreadsGiveBitIdenticalResults) {
  const int saved = parallel::threads();
  ASSERT_GT(scene().mesh.V.rows(), 3000);
  for (const Case c :
       {Case{Method::Subspace, JacobianMode::Fast, "subspace/fast"},
        Case{Method::Subspace, JacobianMode::Exact, "subspace/exact"},
        Case{Method::Full, JacobianMode::Fast, "full/fast"}, Case{Method::Full, JacobianMode::Exact, "full/exact"},
        Case{Method::Arap, JacobianMode::Fast, "arap"},
        Case{Method::Subspace, JacobianMode::Fast, "subspace/fast/reduced", Integration::Reduced},
        Case{Method::Subspace, JacobianMode::Exact, "subspace/exact/reduced", Integration::Reduced},
        Case{Method::Subspace, JacobianMode::Fast, "subspace/fast/gauss-newton", Integration::Full,
             Preconditioner::GaussNewton},
        Case{Method::Subspace, JacobianMode::Fast, "subspace/fast/reduced/gauss-newton", Integration::Reduced,
             Preconditioner::GaussNewton},
        Case{Method::Subspace, JacobianMode::Fast, "subspace/fast/bones", Integration::Full,
             Preconditioner::GaussNewton, true},
        Case{Method::Subspace, JacobianMode::Fast, "subspace/fast/reduced/bones", Integration::Reduced,
             Preconditioner::Constant, true},
        Case{Method::Full, JacobianMode::Fast, "full/fast/bones", Integration::Full, Preconditioner::Constant, true},
        Case{Method::Subspace, JacobianMode::Fast, "subspace/fast/reduced/finished", Integration::Reduced,
             Preconditioner::GaussNewton, false, 60}}) {
    const SolveRecord one = solve_with(1, c);
    ASSERT_FALSE(one.energies.empty()) << c.name;
    if (c.max_iterations > 5) EXPECT_TRUE(one.finished) << c.name << ": " << one.stop_reason;
    for (int threads : {2, 4, 16}) {
      const SolveRecord many = solve_with(threads, c);
      EXPECT_TRUE(bit_identical(one.weights, many.weights)) << c.name << ", " << threads << " threads: W";
      EXPECT_TRUE(bit_identical(one.positions, many.positions)) << c.name << ", " << threads << " threads: positions";
      EXPECT_EQ(one.energies, many.energies) << c.name << ", " << threads << " threads";
      EXPECT_EQ(one.products, many.products) << c.name << ", " << threads << " threads";
      EXPECT_EQ(one.stop_reason, many.stop_reason) << c.name << ", " << threads << " threads";
    }
  }
  parallel::set_threads(saved);
}

}  // namespace
}  // namespace sd
