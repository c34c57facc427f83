#include "core/solver/internal/steps/pcg_step.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <utility>

namespace sd {

namespace {

// A run's (V, A V) pairs: only the newest cg_memory of them can be kept, so only those are held, however long the run.
using Pairs = std::deque<std::pair<Eigen::MatrixXd, Eigen::MatrixXd>>;

// One PCG run, with or without the curvature term; its pairs go to `pairs`, not yet to the memory (the
// preconditioner must stay fixed during a run, and a run whose step is not returned must leave it as it was).
ConstrainedStep solve(const PcgStepProblem& problem, bool curved, int budget, const LbfgsPreconditioner& memory,
                      const Eigen::MatrixXd& b, const Eigen::MatrixXd& c, const Eigen::VectorXd& g,
                      const Eigen::VectorXd& scales, bool volume, const SolverOptions& options,
                      std::unique_ptr<ProjectedPcg>& pcg, Pairs& pairs) {
  ConstrainedStep step;
  PcgOperator op;
  op.apply = [&](const Eigen::MatrixXd& P, Eigen::MatrixXd& AP, Eigen::MatrixXd& image) {
    AP = problem.product(P, image);
    if (curved) problem.curvature(P, AP);
    const double curvature = block_dot(P, AP);
    if (options.cg_memory == 0 || !(curvature > 0.0) || !std::isfinite(curvature)) return;  // add_pair skips these
    pairs.emplace_back(P, AP);
    if (static_cast<int>(pairs.size()) > options.cg_memory) pairs.pop_front();
  };
  op.precondition = [&](const Eigen::MatrixXd& R) { return memory.apply(R, problem.base_preconditioner); };
  // Restoration after every accepted step leaves |g| at rounding level; starting exactly on C^T h = -g would
  // then cost products to move h by that much, which the next restoration does anyway.
  const Eigen::VectorXd g_start = start_constraint(g, scales);
  const bool starts_at_zero = (g_start.array() == 0.0).all();
  pcg = std::make_unique<ProjectedPcg>(op, b, volume ? c : Eigen::MatrixXd(), g_start, problem.image_rows);
  // The budget and cgMaxIterations count the products beyond the start, which spends one per constraint off h = 0:
  // 29 bones on the bar's cage make 63 constraints (the volume, 29 lengths, 11 held middles of three rows), and a cap
  // that counted them left its steps no CG iteration at all (a step of ~1e-6, read as converged at the rest pose).
  pcg->run_further(options.cg_tolerance, std::min(budget, options.cg_max_iterations));

  auto assemble = [&](const Eigen::MatrixXd& du, const Eigen::MatrixXd& dx, const Eigen::VectorXd& lambda) {
    step.du = du;
    step.dx = dx;
    step.lambda = lambda.size() ? lambda : Eigen::VectorXd(Eigen::VectorXd::Zero(c.cols() / 3));
    step.slope = block_dot(du, add_blocks(b, c, step.lambda));
  };
  assemble(pcg->h(), pcg->image(), pcg->lambda());
  const bool moving = step.du.squaredNorm() > 0.0;
  if (moving && !(step.slope < 0.0)) {
    // Rounding, or a start off the constraint, made the inexact step no descent direction: solve tighter.
    pcg->run_further(options.cg_tolerance * 1e-3, options.cg_max_iterations);
    assemble(pcg->h(), pcg->image(), pcg->lambda());
  }
  if (moving && !(step.slope < 0.0) && starts_at_zero && pcg->first_image_known()) {
    // Last resort: the projected preconditioned gradient -proj(b), a descent direction on c.h = 0.
    step.fallbacks = 1;
    assemble(pcg->first_direction(), pcg->first_image(), pcg->lambda());
  }
  step.inner_iterations = pcg->products();
  step.products = pcg->products();
  return step;
}

}  // namespace

ConstrainedStep pcg_step(const PcgStepProblem& problem, LbfgsPreconditioner& memory, const Eigen::MatrixXd& b,
                         const Eigen::MatrixXd& c, const Eigen::VectorXd& g, const Eigen::VectorXd& scales, bool volume,
                         const SolverOptions& options, std::unique_ptr<ProjectedPcg>& pcg) {
  Pairs pairs;
  const bool curved = static_cast<bool>(problem.curvature);
  ConstrainedStep step =
      solve(problem, curved, problem.first_run_products, memory, b, c, g, scales, volume, options, pcg, pairs);
  if (curved && (pcg->broken() || step.fallbacks > 0)) {
    // The curvature made A indefinite on the constraints' tangent space (far from a minimum, where the multipliers
    // are large), or its step was no descent direction: the Gauss-Newton matrix alone is positive semidefinite.
    const int spent = step.products;
    pairs.clear();
    step = solve(problem, false, std::numeric_limits<int>::max(), memory, b, c, g, scales, volume, options, pcg, pairs);
    step.products += spent;
    step.inner_iterations += spent;
  }
  memory.resize(options.cg_memory);  // (also applies a changed option)
  for (const auto& [P, AP] : pairs) memory.add_pair(P, AP);
  return step;
}

}  // namespace sd
