#include "core/solver/internal/gauss_newton.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/timer.h"

namespace sd {

void fill_part_stats(IterationStats& s, const Eigen::VectorXd& g, const Eigen::VectorXd& lambda,
                     const DeformationEnergy& energy) {
  const Eigen::VectorXd& rest = energy.rest_constraint_volumes();
  s.part_volume_change.resize(static_cast<size_t>(g.size()));
  s.part_lambda.assign(static_cast<size_t>(g.size()), 0.0);
  for (Eigen::Index k = 0; k < g.size(); ++k) {
    s.part_volume_change[k] = g[k] / std::abs(rest[k]);
    if (k < lambda.size()) s.part_lambda[k] = lambda[k];
  }
}

namespace {

void fill_skeleton_stats(IterationStats& s, const EnergyEvaluation& e, const Eigen::VectorXd& lambda,
                         const DeformationEnergy& energy) {
  const SkeletonReport report = energy.skeleton()->report(e.skeleton_points, lambda);
  s.bone_length_error = report.max_length_error();
  s.bone_straightness_error = report.max_straightness_error();
  for (const BoneReport& b : report.bones) s.bone_lambda.push_back(b.lambda);
}

void fill_point_stats(IterationStats& s, const EnergyEvaluation& e, double regularization,
                      const Eigen::VectorXd& lambda, const HardConstraints& hard, const DeformationEnergy& energy) {
  s.merit = e.energy + regularization + multiplier_dot(lambda, hard.values(e));
  s.regularization_energy = regularization;
  s.energy = e.energy;
  s.laplacian_energy = e.laplacian_energy;
  s.position_energy = e.position_energy;
  s.straightness_energy = e.straightness_energy;
  s.volume = e.volume;
  s.volume_rel_error = (e.volume - energy.rest_volume()) / energy.rest_volume();
  // lambda: the volume's multipliers first, then the skeleton's (hard_constraints.h).
  const Eigen::VectorXd volume_lambda = lambda.head(std::min<Eigen::Index>(lambda.size(), hard.volume_count()));
  s.lambda = hard.volume_count() == 1 && volume_lambda.size() == 1 ? volume_lambda[0] : 0.0;
  if (energy.has_volume_parts()) fill_part_stats(s, e.constraint, volume_lambda, energy);
  if (energy.skeleton())
    fill_skeleton_stats(
        s, e, lambda.size() == hard.count() ? Eigen::VectorXd(lambda.tail(hard.skeleton_count())) : Eigen::VectorXd(),
        energy);
}

void fill_step_stats(IterationStats& s, const ConstrainedStep& step) {
  s.inner_iterations = step.inner_iterations;
  s.products = step.products;
  s.passes = step.passes;
  s.fallbacks = step.fallbacks;
  s.slope = step.slope;
}

// Largest relative volume error an accepted step may keep after restoration; restoration normally reaches
// ~1e-15, so only steps whose volume cannot be restored are affected.
constexpr double kRestoredVolumeTolerance = 1e-9;

// A stop because the merit no longer decreases is a convergence only where the Gauss-Newton model agrees that
// there is nothing left to gain: its predicted decrease (-slope / 2) below this fraction of the merit. Far from
// a minimiser (targets far beyond the mesh's scale, a tolerance tighter than doubles resolve) the model still
// predicts a large decrease that the line search cannot realise: that is a stall, and must not read
// "converged".
constexpr double kStationaryRel = 1e-6;

// Steps shorter than this fraction of the bounding-box diagonal move coordinates by rounding noise: a smaller
// stepTolerance (0 is allowed) is clamped to it, which also bounds the line search's number of trials.
constexpr double kSmallestResolvableStep = 1e-14;

bool is_stationary(const ConstrainedStep& step, double merit) {
  return -step.slope <= kStationaryRel * std::abs(merit);
}

// The step's restoring directions, and the iteration's point (X, its skeleton's points) where those of its
// nonlinear constraints alone are made when a trial can use them.
struct Restoring {
  const RestoringDirections& all;
  NonlinearRestoration& nonlinear;
  const Vertices& X;
  const Eigen::MatrixXd& points;
};

// Puts a line-search trial (Xs, Us, es) back on the hard constraints along the step's restoring directions (the
// nonlinear ones' alone where they serve). Returns false, leaving the trial unchanged, when they cannot be
// restored there.
bool restore_trial(const Objective& objective, const HardConstraints& hard, const Restoring& restoring, Vertices& Xs,
                   Eigen::MatrixXd& Us, EnergyEvaluation& es) {
  const DeformationEnergy& energy = objective.energy();
  Vertices Xr = Xs;
  Eigen::MatrixXd Ur = Us;
  const Eigen::VectorXd g = hard.values(es);
  const RestoringDirections* nonlinear =
      restoring.nonlinear.for_trial(hard, restoring.all, restoring.X, restoring.points, g);
  // Newton is cheap (O(#V) per step; on the cubic psi(X + t r) for the global volume): allow enough steps for
  // the first, long steps of a drag, whose volume change can be several percent.
  const double remaining = restore_constraints(hard, energy, Xr, Ur, nonlinear ? *nonlinear : restoring.all,
                                               /*max_newton=*/8, es.skeleton_points, g);
  if (!(std::abs(remaining) <= kRestoredVolumeTolerance)) return false;
  // The cubic's coefficients lose digits when the trial is far larger than the rest mesh; the volume evaluated
  // at the restored point is the check that counts.
  const EnergyEvaluation er = objective.evaluate(Xr, Ur);
  if (!er.finite() || !(hard.relative_error(hard.values(er)) <= kRestoredVolumeTolerance)) return false;
  Xs = std::move(Xr);
  Us = std::move(Ur);
  es = er;
  return true;
}

// The accepted point of a line search (after volume restoration).
struct Accepted {
  double alpha = 0;
  Vertices X;
  Eigen::MatrixXd U;
  EnergyEvaluation e;
};

// Armijo backtracking (docs/method.md section 7): alpha = 1, c2, c2^2, ... while alpha max|dx| >= the step
// tolerance. Trials are O(#V): dx is cached in X space. A trial that passes Armijo is then put back on the volume
// constraint; if that fails (a long step can fold the mesh so that no point on the restoring line has the rest
// volume) the trial is rejected like one that failed Armijo, because the merit's lambda g term can reward exactly
// such constraint-breaking steps. The restored point must pass Armijo too: a long step can change the volume so
// much that restoring it costs more than the step gained (a vertex pulled away from a fixed group 0.09 from it,
// where the subspace's step was 5 times the model's size), and a shorter trial then restores at a cost of order
// alpha^2 against a gain of order alpha. Every trial is recorded in s.line_search.
std::optional<Accepted> armijo_search(const Objective& objective, const HardConstraints& hard,
                                      const ConstrainedStep& step, GaussNewtonState& state, const EnergyEvaluation& e,
                                      double merit0, double step_tolerance, const SolverOptions& options,
                                      IterationStats& s) {
  const bool restore = !hard.empty() && !step.restore.empty();
  const Restoring restoring{step.restore, state.restoration, state.X, e.skeleton_points};
  for (double alpha = 1.0; alpha * s.step_length >= step_tolerance; alpha *= options.armijo_c2) {
    Accepted trial{alpha, state.X + alpha * step.dx, state.U + alpha * step.du, {}};
    trial.e = objective.evaluate(trial.X, trial.U);
    LineSearchTrial record;
    record.alpha = alpha;
    record.merit =
        trial.e.energy + objective.regularization_energy(trial.U) + multiplier_dot(step.lambda, hard.values(trial.e));
    record.sufficient_decrease = trial.e.finite() && record.merit <= merit0 + options.armijo_c1 * alpha * step.slope;
    record.restored = record.sufficient_decrease &&
                      (!restore || restore_trial(objective, hard, restoring, trial.X, trial.U, trial.e));
    if (record.restored && restore) {
      const double restored_merit =
          trial.e.energy + objective.regularization_energy(trial.U) + multiplier_dot(step.lambda, hard.values(trial.e));
      record.restored = restored_merit <= merit0 + options.armijo_c1 * alpha * step.slope;
    }
    s.line_search.push_back(record);
    ++s.line_search_trials;
    if (record.restored) return trial;
  }
  return std::nullopt;
}

// Why an iteration that could not lower the merit stopped: converged where the model predicts nothing more to
// gain, stalled otherwise.
void finish_without_decrease(StepResult& result, StopCode converged_code, const ConstrainedStep& step, double merit) {
  if (is_stationary(step, merit)) {
    result.finish(converged_code);
    return;
  }
  result.finish(StopCode::Stalled,
                "stalled: the line search cannot lower the merit although the Gauss-Newton model predicts a decrease "
                "of " +
                    std::to_string(-0.5 * step.slope / std::abs(merit)) +
                    " of it (targets far beyond the mesh's scale, or tolerances tighter than the arithmetic resolves); "
                    "the last good iterate is kept");
}

// The step (h, dx, lambda, slope) is usable: every part finite.
bool finite_step(const ConstrainedStep& step) {
  return step.dx.allFinite() && step.du.allFinite() && step.lambda.allFinite() && std::isfinite(step.slope);
}

// The energy at the state's positions: the previous call's evaluation with its handle terms refreshed (the targets
// or the weight may have changed since), or a new one.
EnergyEvaluation current_evaluation(const Objective& objective, GaussNewtonState& state) {
  EnergyEvaluation e;
  if (state.evaluation) {
    e = std::move(*state.evaluation);
    objective.update_position_terms(state.X, e);
  } else {
    e = objective.evaluate(state.X, state.U);
  }
  state.evaluation.reset();
  return e;
}

}  // namespace

const EnergyJacobian& FullIntegration::jacobian_at(const Vertices& X) {
  if (J_) energy_->update_jacobian(X, *J_);
  else J_.emplace(energy_->jacobian(X));
  return *J_;
}

ConstrainedStep FullIntegration::step(const EnergyEvaluation& e, const Vertices& X, const Eigen::MatrixXd& U,
                                      const SolverOptions& options) {
  return steps_->compute(jacobian_at(X), e, X, U, options);
}

StepResult gauss_newton(const DeformationEnergy& energy, StepSolver& steps, GaussNewtonState& state, int max_iterations,
                        const SolverOptions& options, StopCode cap) {
  FullIntegration objective(energy, steps);
  return gauss_newton(objective, state, max_iterations, options, cap);
}

StepResult gauss_newton(Objective& objective, GaussNewtonState& state, int max_iterations, const SolverOptions& options,
                        StopCode cap) {
  const DeformationEnergy& energy = objective.energy();
  const HardConstraints hard(energy, options.volume);
  StepResult result;
  if (energy.handle_vertices().empty()) {
    result.finish(StopCode::NoHandles);
    return result;
  }
  const double step_tolerance = std::max(options.step_tolerance, kSmallestResolvableStep) * energy.rest_diagonal();
  EnergyEvaluation e = current_evaluation(objective, state);
  if (!e.finite()) {
    result.finish(StopCode::NumericalFailure,
                  "numerical failure: the energy at the current positions is not finite (targets too far?)");
    return result;
  }

  // A lagged step (constrained_step.h) that cannot be taken is made again at once, at the same targets, with fresh
  // constraint gradients: that iteration is counted once, with both attempts' time, products and passes. At most
  // one retry per iteration, whatever a step solver does.
  IterationStats discarded;
  bool retried = false;
  for (int k = 0; k < max_iterations && !result.stopped(); ++k) {
    const Timer timer;
    const bool retry = std::exchange(retried, false);
    IterationStats s;
    const ConstrainedStep step = objective.step(e, state.X, state.U, options);
    state.restoration.next_step(step.restore);  // whether the step solver kept its restoring directions
    fill_step_stats(s, step);
    const double earlier_ms = retry ? discarded.ms : 0.0;
    if (retry) {
      s.inner_iterations += discarded.inner_iterations;
      s.products += discarded.products;
      s.passes += discarded.passes;
    }
    auto retry_lagged = [&] {
      if (!step.lagged || retry) return false;
      discarded = s;
      discarded.ms = timer.ms();
      retried = true;
      --k;
      return true;
    };
    if (!finite_step(step)) {
      if (retry_lagged()) continue;
      result.finish(StopCode::NumericalFailure,
                    "numerical failure: the Gauss-Newton step is not finite; the last good iterate is kept");
      break;
    }
    // The merit: the energy, the step solver's regularisation of its unknowns (the cage subspace's; 0 in the
    // full space) and lambda . g.
    const double regularization0 = objective.regularization_energy(state.U);
    const double merit0 = e.energy + regularization0 + multiplier_dot(step.lambda, hard.values(e));
    s.merit_start = merit0;
    s.step_length = max_row_norm(step.dx);

    // Records an iteration that leaves the positions where they are (so a solve's last entry says why it stopped).
    auto record_unmoved = [&] {
      fill_point_stats(s, e, regularization0, step.lambda, hard, energy);
      s.iteration = ++state.iteration;
      s.ms = earlier_ms + timer.ms();
      result.iterations.push_back(s);
    };
    if (s.step_length < step_tolerance) {
      if (retry_lagged()) continue;
      record_unmoved();
      result.finish(StopCode::StepTolerance);
      break;
    }
    if (!(step.slope < 0.0)) {
      if (retry_lagged()) continue;
      record_unmoved();
      result.finish(StopCode::NoDescent);
      break;
    }
    std::optional<Accepted> accepted =
        armijo_search(objective, hard, step, state, e, merit0, step_tolerance, options, s);
    if (!accepted) {
      if (retry_lagged()) continue;
      record_unmoved();
      finish_without_decrease(result, StopCode::NoDecrease, step, merit0);
      break;
    }
    const double regularization_new = objective.regularization_energy(accepted->U);  // after restoration moved U
    const double merit_new =
        accepted->e.energy + regularization_new + multiplier_dot(step.lambda, hard.values(accepted->e));
    if (!(merit_new <= merit0)) {  // restoration undid the decrease: at rounding level near the end, else a stall
      if (retry_lagged()) continue;
      record_unmoved();
      finish_without_decrease(result, StopCode::MeritTolerance, step, merit0);
      break;
    }
    s.alpha = accepted->alpha;
    s.step = max_row_norm(Eigen::MatrixXd(accepted->X - state.X));
    state.X = std::move(accepted->X);
    state.U = std::move(accepted->U);
    e = std::move(accepted->e);
    fill_point_stats(s, e, regularization_new, step.lambda, hard, energy);
    s.iteration = ++state.iteration;
    s.ms = earlier_ms + timer.ms();
    result.iterations.push_back(s);
    if (step.lagged) {
      // Its slope and decrease are the lagged model's: the next iteration, at the same targets, decides.
    } else if (s.alpha * s.step_length < step_tolerance) {
      result.finish(StopCode::StepTolerance);
    } else if (merit0 - merit_new <= options.merit_tolerance * std::abs(merit0)) {
      // The actual decrease is below the tolerance: converged if the model agrees, else stalled.
      finish_without_decrease(result, StopCode::MeritTolerance, step, merit0);
    } else if (-step.slope <= options.merit_tolerance * std::abs(merit0)) {
      // The Gauss-Newton model's predicted decrease for this step (-slope is twice it) is below the tolerance:
      // further iterations cannot change the merit measurably.
      result.finish(StopCode::MeritTolerance);
    }
  }
  if (!result.stopped()) result.finish(cap);
  state.evaluation = std::move(e);
  return result;
}

}  // namespace sd
