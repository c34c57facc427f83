#include "core/solver/methods/subspace_method.h"

#include <algorithm>

#include "core/solver/internal/energy/vertex_stiffness.h"

namespace sd {
namespace {

// The vertices that hold most of the Laplacian term's Gauss-Newton matrix (vertex_stiffness.h): at most as many as
// keep the rotation terms' 3m x 3m sums within kRotationTermsBudget multiply-adds (two sums of 3 rows each).
constexpr double kStiffRatio = 0.5;
constexpr double kRotationTermsBudget = 1.2e9;

}  // namespace

SubspaceMethod::SubspaceMethod(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                               bool cage, double cage_regularization)
    : energy_(&energy), W_(&W), U0_(&U0), step_(std::make_unique<SubspaceStep>(energy, W)) {
  step_->set_rest_unknowns(U0);
  // Only a cage has vertices that can wander off while barely moving the mesh (cage_regularization.h).
  if (cage) step_->regularize_cage(U0, cage_regularization);
  // The fast steps' factor preconditioner adds the rotation terms of the stiffest vertices (rotation_terms.h).
  step_->set_rotation_terms(
      [this](const Eigen::MatrixXd& U) {
        if (!rotation_terms_) rotation_terms_ = std::make_unique<RotationTerms>(*energy_, *W_, *U0_, stiff());
        return rotation_terms_->matrix(U);
      },
      [this] { return static_cast<int>(stiff().size()); });
}

StepResult SubspaceMethod::run(GaussNewtonState& state, int k, const SolverOptions& options, StopCode cap) {
  prepare(options);  // the step is factored for the current handles, whichever integration runs
  if (options.integration != Integration::Reduced) return gauss_newton(*energy_, *step_, state, k, options, cap);
  StepResult result = gauss_newton(reduced(), state, k, options, cap);
  for (IterationStats& s : result.iterations) s.samples = reduced_->sample_count();
  return result;
}

void SubspaceMethod::forget_history() {
  step_->forget_history();
  if (reduced_) reduced_->forget_history();
}

const std::vector<int>& SubspaceMethod::stiff() {
  if (!stiff_) {
    const double m = W_->cols();
    const int limit = static_cast<int>(std::min(1000.0, kRotationTermsBudget / (27.0 * m * m)));
    stiff_ = stiff_vertices(*energy_, vertex_stiffness(*energy_, *W_), kStiffRatio, limit);
  }
  return *stiff_;
}

const Cubature& SubspaceMethod::cubature() {
  if (!cubature_) {
    // At least twice as many samples as basis vectors (each gives 3 of the 3m rows the unknowns need), the stiff
    // vertices among them exactly. A mesh of at most max_samples vertices is summed whole: no stiffness pass.
    CubatureOptions rule;
    rule.max_samples = std::max(rule.max_samples, 2 * static_cast<int>(W_->cols()));
    if (energy_->vertex_count() > rule.max_samples) rule.exact_vertices = stiff();
    cubature_ = fit_cubature(*energy_, *W_, *U0_, rule);
  }
  return *cubature_;
}

ReducedSubspace& SubspaceMethod::reduced() {
  if (!reduced_) reduced_ = std::make_unique<ReducedSubspace>(*energy_, *W_, *U0_, *step_, cubature());
  return *reduced_;
}

}  // namespace sd
