// The fast step's solve, shared by the cage or spectral subspace (subspace_step.h), its reduced integration
// (reduced_subspace.h) and the full space (full_space_step.h, with options.cg_memory 0): projected PCG
// (projected_pcg.h) on A h = -b subject to C^T h = -g, preconditioned by a constant N^-1 updated with the last
// products' L-BFGS pairs (lbfgs_preconditioner.h), with two fallbacks when the inexact step is no descent direction: a
// tighter solve, then the projected preconditioned gradient.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>

#include "core/solver/internal/steps/constrained_step.h"
#include "core/solver/internal/steps/lbfgs_preconditioner.h"
#include "core/solver/internal/steps/projected_pcg.h"
#include "core/solver/solver_types.h"

namespace sd {

struct PcgStepProblem {
  // A V for a block V (m by 3), and its image W V (#V by 3, or 0 rows where the caller maps the step itself).
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd& V, Eigen::MatrixXd& image)> product;
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd& R)> base_preconditioner;  // N^-1 R
  Eigen::Index image_rows = 0;
  // Optional: AV += the hard constraints' curvature times V (length_curvature.h), added to each product. Where the
  // PCG meets non-positive curvature with it, or its step needed the projected-gradient fallback, the step is solved
  // again without it: both runs' products are counted, and only the second run's pairs update the memory.
  std::function<void(const Eigen::MatrixXd& V, Eigen::MatrixXd& AV)> curvature;
  // At most this many products in the first run beyond its start on the constraints (the factor preconditioner's
  // rent: gauss_newton_factor.h), within options.cg_max_iterations. The tighter solve and the run without the
  // curvature keep the option's budget.
  int first_run_products = std::numeric_limits<int>::max();
};

// The step (du, its image as dx, lambda, slope and counts; no restoration directions). `pcg` receives the solver
// for the caller's use of its constraint directions. Only the newest options.cg_memory pairs of this run are
// kept for the memory, however many products the run takes.
ConstrainedStep pcg_step(const PcgStepProblem& problem, LbfgsPreconditioner& memory, const Eigen::MatrixXd& b,
                         const Eigen::MatrixXd& c, const Eigen::VectorXd& g, const Eigen::VectorXd& scales, bool volume,
                         const SolverOptions& options, std::unique_ptr<ProjectedPcg>& pcg);

}  // namespace sd
