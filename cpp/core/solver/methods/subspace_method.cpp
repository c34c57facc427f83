#include "core/solver/methods/subspace_method.h"

#include <algorithm>
#include <numeric>
#include <utility>

#include "core/solver/internal/energy/vertex_stiffness.h"
#include "core/solver/internal/reduced/finishing_integration.h"
#include "core/solver/internal/reduced/rotation_clusters.h"
#include "core/solver/internal/reduced/sampled_laplacian.h"
#include "core/timer.h"

namespace sd {
namespace {

// The vertices that hold most of the Laplacian term's Gauss-Newton matrix (vertex_stiffness.h): at most as many as
// keep their rotation terms' 3m x 3m sums within the factor's budget (factor_rotation_terms.h).
constexpr double kStiffRatio = 0.5;
// The reduced rule (prepare_reduced): vertices summed exactly, else clusters, and the held-out poses it is tested on.
constexpr int kReducedVertices = 800;
constexpr int kTestPoses = 8;
constexpr unsigned kTestSeed = 1;
// A reduced solve's finishing iterations (docs/method.md section 17.3) stop once what is left to move is below this
// fraction of the diagonal: the proposed step, and the tail its shrinking predicts (finished() below). The distance
// left to the full shape was then 1e-7 to 2e-5 of the diagonal on the real models whose rule passes its test, which
// the eye does not see (scripts/bench/big.mjs counts a shape still to the eye within the same 1e-4). A tighter
// answer is full integration's.
constexpr double kFinishingStepTolerance = 1e-4;  // as finish_reduced's stop reason says
// At most this many finishing steps with the rule's matrix, then full integration's. On the real models the first
// steps took roughly half of the distance to the full shape off each (more on the moomoo, less on the cow); where
// they converge slowly (the spiky box in its 8-vertex cage: 13% per step), full steps finish sooner.
constexpr int kFinishingSteps = 4;

// Appends `more`'s iterations to `result`, whose stop becomes `more`'s.
void append(StepResult& result, const StepResult& more) {
  result.iterations.insert(result.iterations.end(), more.iterations.begin(), more.iterations.end());
  result.finish(more.stop, more.stop_reason);
}

// Whether finishing steps that proposed `previous` and then `step` (vertex moves) have come within `tolerance` of their
// fixed point. They converge linearly where the rule's matrix steps (or the full ones far from the minimum): each
// step about r times the last, so that after this one about step r / (1 - r) is left, asked to be below half the
// tolerance because r creeps up as they converge. A small step alone was not enough: on the bar turned 90 degrees
// in its spectral basis (r = 0.65) the step 9e-5 left 1.7e-4; on the bar turned 150 degrees in its cage (r = 0.56)
// the tail's estimate alone, 7e-5, left 1.1e-4.
bool finished(double step, double previous, double tolerance) {
  if (step < 0.1 * tolerance) return true;  // nothing left to move (a confirmation)
  if (!(step < tolerance) || !(previous > 0.0)) return false;
  const double r = step / previous;
  return r < 1.0 && step * r < 0.5 * tolerance * (1.0 - r);
}

StepResult mark_finishing(StepResult result) {
  for (IterationStats& s : result.iterations) s.finishing = true;
  return result;
}

}  // namespace

SubspaceMethod::SubspaceMethod(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                               bool cage, double cage_regularization)
    : energy_(&energy), W_(&W), U0_(&U0), step_(std::make_unique<SubspaceStep>(energy, W)) {
  step_->set_rest_unknowns(U0);
  // Only a cage has vertices that can wander off while barely moving the mesh (cage_regularization.h).
  if (cage) step_->regularize_cage(U0, cage_regularization);
  // The fast steps' factor preconditioner adds the rotation terms: the stiffest vertices' exactly, the others'
  // through clusters (factor_rotation_terms.h).
  step_->set_rotation_terms([this](const Eigen::MatrixXd& U) { return factor_terms().matrix(U); },
                            [this](bool exact) { return factor_units(exact); });
}

StepResult SubspaceMethod::run(GaussNewtonState& state, int k, const SolverOptions& options, StopCode cap) {
  prepare(options);  // the step is factored for the current handles, whichever integration runs
  if (options.integration != Integration::Reduced) {
    const StepResult result = gauss_newton(*energy_, *step_, state, k, options, cap);
    // Converged on the full energy: a reduced solve at these targets has only to confirm it, not to start on the
    // rule (whose minimiser lies elsewhere).
    if (result.converged) converged_here(kFinishingSteps);
    else rule_converged_.reset();
    return result;
  }
  ReducedSubspace& rule = reduced();
  StepResult result;
  if (!rule_->clusters || !finishing()) {  // the exact sum is the full energy: nothing to finish
    rule_converged_.reset();               // whatever converged before was at other targets
    enter(Phase::Rule, state);
    result = gauss_newton(rule, state, k, options, cap);
    for (IterationStats& s : result.iterations) s.samples = rule.sample_count();
    // A stall of the rule is its own minimiser's trouble (targets it fits poorly): the finishing iterations, on the
    // full energy, go on from there. Every other stop (the cap, a time limit, a failure) is the caller's.
    const bool stalled = result.stop == StopCode::Stalled;
    if (!rule_->clusters || !(result.converged || stalled)) return result;
    converged_here(0);
    k -= static_cast<int>(result.iterations.size());
    if (k <= 0) {
      result.finish(cap);  // the finishing iterations are still to come
      return result;
    }
  }
  enter(Phase::Finishing, state);
  append(result, finish_reduced(state, k, options, cap));
  return result;
}

StepResult SubspaceMethod::finish_reduced(GaussNewtonState& state, int k, const SolverOptions& options, StopCode cap) {
  FinishingIntegration with_rule(*energy_, *step_, *reduced_);
  FullIntegration full(*energy_, *step_);
  // A rule that failed its test is no model of the full matrix: full integration's steps only.
  const bool rule_serves = rule_->test_error <= kReducedTestErrorLimit;
  const double tolerance = kFinishingStepTolerance * energy_->rest_diagonal();
  StepResult result;
  // One iteration at a time, so that the finishing tolerance ends them without being the line search's floor too.
  for (int i = 0; i < k; ++i) {
    int& taken = rule_converged_->finishing_steps;
    const bool by_rule = rule_serves && taken < kFinishingSteps;
    taken += by_rule ? 1 : 0;
    const StepResult one = gauss_newton(by_rule ? static_cast<Objective&>(with_rule) : full, state, 1, options, cap);
    append(result, one);
    if (one.stop != cap) {
      if (one.converged || !by_rule) break;  // converged, or stopped by the loop's own rules
      taken = kFinishingSteps;               // the rule's matrix found no step (stalled): full steps from now on
      result.finish(cap);
      continue;
    }
    // The proposed (undamped) step: small when the model finds the shape close, however the line search damped it.
    const double step = one.iterations.back().step_length;
    const double previous = std::exchange(rule_converged_->last_step, step);
    if (finished(step, previous, tolerance)) {
      result.finish(StopCode::StepTolerance,
                    "converged: the finishing steps of the reduced solve leave less than 1e-4 of the diagonal to move "
                    "(the last proposed step and what its shrinking predicts after it)");
      break;
    }
  }
  return mark_finishing(result);
}

void SubspaceMethod::converged_here(int finishing_steps) {
  rule_converged_ =
      ConvergedAt{energy_->targets(), energy_->skeleton_version(), energy_->volume_parts_version(), finishing_steps};
}

bool SubspaceMethod::finishing() const {
  return rule_converged_ && rule_converged_->targets.rows() == energy_->targets().rows() &&
         rule_converged_->targets == energy_->targets() &&
         rule_converged_->skeleton_version == energy_->skeleton_version() &&
         rule_converged_->volume_parts_version == energy_->volume_parts_version();
}

void SubspaceMethod::enter(Phase phase, GaussNewtonState& state) {
  if (phase != phase_) state.evaluation.reset();  // the rule's energy is not the full one
  phase_ = phase;
}

void SubspaceMethod::forget_history() {
  step_->forget_history();
  if (reduced_) reduced_->forget_history();
  rule_converged_.reset();
}

const std::vector<int>& SubspaceMethod::stiff() {
  if (!stiff_) {
    const int limit = stiff_vertex_limit(static_cast<int>(W_->cols()));
    stiff_ = stiff_vertices(*energy_, vertex_stiffness(*energy_, *W_), kStiffRatio, limit);
  }
  return *stiff_;
}

FactorRotationTerms& SubspaceMethod::factor_terms() {
  if (!rotation_terms_)
    rotation_terms_ = std::make_unique<FactorRotationTerms>(*energy_, *W_, *U0_, step_->laplacian_gram(), stiff());
  return *rotation_terms_;
}

int SubspaceMethod::factor_units(bool exact) {
  // Once made, the clusters it holds (a component no sample reached adds one).
  if (rotation_terms_) return rotation_terms_->units();
  const int m = static_cast<int>(W_->cols());
  // Not exact: at most as many stiff vertices as the budget allows, without looking for them (a pass over W).
  const int stiff_count = exact || stiff_ ? static_cast<int>(stiff().size()) : stiff_vertex_limit(m);
  return stiff_count + FactorRotationTerms::cluster_count(energy_->vertex_count(), m);
}

void SubspaceMethod::prepare_factor(const SolverOptions& options) {
  if (step_->factor_wanted(options)) factor_terms();
}

const SubspaceMethod::ReducedRule& SubspaceMethod::prepare_reduced() {
  if (!reduced_) {
    const double t0 = now_ms();
    // At least twice as many vertices or clusters as basis vectors (each gives 3 of the 3m rows the unknowns need).
    const int limit = std::max(kReducedVertices, 2 * static_cast<int>(W_->cols()));
    const int n = energy_->vertex_count();
    ReducedRule rule;
    rule.candidates = n;
    if (n <= limit) {
      std::vector<int> every(static_cast<size_t>(n));
      std::iota(every.begin(), every.end(), 0);
      reduced_ = std::make_unique<ReducedSubspace>(
          *energy_, *W_, *U0_, *step_,
          std::make_unique<SampledLaplacian>(*energy_, *W_, *U0_, every, Eigen::VectorXd::Ones(n)));
    } else {
      auto clusters = std::make_unique<RotationClusters>(
          *energy_, *W_, *U0_, step_->laplacian_gram(),
          surface_clusters(energy_->rest_positions(), energy_->coordinates(), limit));
      rule.clusters = true;
      rule.test_error = cluster_test_error(*clusters, *energy_, *W_, *U0_, kTestPoses, kTestSeed);
      reduced_ = std::make_unique<ReducedSubspace>(*energy_, *W_, *U0_, *step_, std::move(clusters));
    }
    rule.samples = reduced_->sample_count();
    rule.ms = now_ms() - t0;
    rule_ = rule;
  }
  return *rule_;
}

ReducedSubspace& SubspaceMethod::reduced() {
  prepare_reduced();
  return *reduced_;
}

}  // namespace sd
