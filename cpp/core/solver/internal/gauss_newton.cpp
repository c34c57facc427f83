#include "core/solver/internal/gauss_newton.h"

#include <chrono>
#include <cmath>
#include <optional>

#include "core/error.h"

namespace sd {
namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

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

void fill_point_stats(IterationStats& s, const EnergyEvaluation& e, const Eigen::VectorXd& lambda,
                      const DeformationEnergy& energy) {
  s.merit = e.energy + multiplier_dot(lambda, e.constraint);
  s.energy = e.energy;
  s.laplacian_energy = e.laplacian_energy;
  s.position_energy = e.position_energy;
  s.volume = e.volume;
  s.volume_rel_error = (e.volume - energy.rest_volume()) / energy.rest_volume();
  s.lambda = lambda.size() == 1 ? lambda[0] : 0.0;
  if (energy.has_volume_parts()) fill_part_stats(s, e.constraint, lambda, energy);
}

void fill_step_stats(IterationStats& s, const ConstrainedStep& step) {
  s.inner_iterations = step.inner_iterations;
  s.products = step.products;
  s.passes = step.passes;
  s.fallbacks = step.fallbacks;
}

// Largest relative volume error an accepted step may keep after restoration; restoration normally reaches
// ~1e-15, so only steps whose volume cannot be restored are affected.
constexpr double kRestoredVolumeTolerance = 1e-9;

}  // namespace

// Puts a line-search trial (Xs, Us, es) back on the volume constraint(s) along the step's restoring directions.
// Returns false, leaving the trial unchanged, when the volume cannot be restored there.
bool restore_trial(const DeformationEnergy& energy, const ConstrainedStep& step, Vertices& Xs, Eigen::MatrixXd& Us,
                   EnergyEvaluation& es) {
  Vertices Xr = Xs;
  Eigen::MatrixXd Ur = Us;
  // Newton is cheap (O(#V) per step; on the cubic psi(X + t r) for the global volume): allow enough steps for
  // the first, long steps of a drag, whose volume change can be several percent.
  const double remaining = restore_volume(energy, Xr, Ur, step.restore_dx, step.restore_du, /*max_newton=*/8);
  if (!(std::abs(remaining) <= kRestoredVolumeTolerance)) return false;
  const EnergyEvaluation er = energy.evaluate(Xr);
  if (!er.finite()) return false;
  Xs = std::move(Xr);
  Us = std::move(Ur);
  es = er;
  return true;
}

StepResult gauss_newton(const DeformationEnergy& energy, StepSolver& steps, GaussNewtonState& state,
                        int max_iterations, const SolverOptions& options, StopCode cap) {
  StepResult result;
  if (energy.handle_vertices().empty()) {
    result.finish(StopCode::NoHandles);
    return result;
  }
  const double step_tolerance = options.step_tolerance * bounding_box_diagonal(energy.rest_positions());
  EnergyEvaluation e;
  if (state.evaluation) {
    e = std::move(*state.evaluation);
    energy.update_position_terms(state.X, e);  // the targets or the weight may have changed since
  } else {
    e = energy.evaluate(state.X);
  }
  state.evaluation.reset();
  if (!e.finite()) {
    result.finish(StopCode::NumericalFailure,
                  "numerical failure: the energy at the current positions is not finite (targets too far?)");
    return result;
  }

  bool stopped = false;
  std::optional<EnergyJacobian> J;  // kept across iterations so its sparse storage is reused
  for (int k = 0; k < max_iterations && !stopped; ++k) {
    const double t0 = now_ms();
    IterationStats s;
    if (J) energy.update_jacobian(state.X, *J);
    else J.emplace(energy.jacobian(state.X));
    const ConstrainedStep step = steps.compute(*J, e, state.X, options);
    fill_step_stats(s, step);
    if (!step.dx.allFinite() || !step.du.allFinite() || !step.lambda.allFinite() || !std::isfinite(step.slope)) {
      result.finish(StopCode::NumericalFailure,
                    "numerical failure: the Gauss-Newton step is not finite; the last good iterate is kept");
      break;
    }
    const double merit0 = e.energy + multiplier_dot(step.lambda, e.constraint);
    const double dx_max = max_row_norm(step.dx);

    auto finish_without_moving = [&](StopCode code) {
      fill_point_stats(s, e, step.lambda, energy);
      s.iteration = ++state.iteration;
      s.ms = now_ms() - t0;
      result.iterations.push_back(s);
      result.finish(code);
      stopped = true;
    };
    if (dx_max < step_tolerance) {
      finish_without_moving(StopCode::StepTolerance);
      break;
    }
    if (!(step.slope < 0.0)) {
      finish_without_moving(StopCode::NoDescent);
      break;
    }

    // Armijo backtracking (docs/method.md section 7). Trials are O(#V): dx is cached in X space. A trial that passes
    // Armijo is then put back on the volume constraint; if that fails (a long step can fold the mesh so that
    // no point on the restoring line has the rest volume) the trial is rejected like one that failed Armijo,
    // because the merit's lambda g term can reward exactly such constraint-breaking steps.
    double alpha = 1.0;
    bool accepted = false;
    Vertices Xs;
    Eigen::MatrixXd Us;
    EnergyEvaluation es;
    while (true) {
      ++s.line_search_trials;
      Xs = state.X + alpha * step.dx;
      es = energy.evaluate(Xs);
      const double merit = es.energy + multiplier_dot(step.lambda, es.constraint);
      if (es.finite() && merit <= merit0 + options.armijo_c1 * alpha * step.slope) {
        Us = state.U + alpha * step.du;
        if (!options.volume || step.restore_dx.size() == 0 || restore_trial(energy, step, Xs, Us, es)) {
          accepted = true;
          break;
        }
      }
      alpha *= options.armijo_c2;
      if (!(alpha * dx_max >= step_tolerance)) break;
    }
    if (!accepted) {
      finish_without_moving(StopCode::NoDecrease);
      break;
    }
    const double merit_new = es.energy + multiplier_dot(step.lambda, es.constraint);
    if (!(merit_new <= merit0)) {  // restoration undid the decrease: only at rounding level, near the end
      finish_without_moving(StopCode::MeritTolerance);
      break;
    }
    s.step = max_row_norm(Eigen::MatrixXd(Xs - state.X));
    state.X = std::move(Xs);
    state.U = std::move(Us);
    e = es;
    fill_point_stats(s, e, step.lambda, energy);
    s.iteration = ++state.iteration;
    s.ms = now_ms() - t0;
    result.iterations.push_back(s);
    if (alpha * dx_max < step_tolerance) {
      result.finish(StopCode::StepTolerance);
      stopped = true;
    } else if (merit0 - merit_new <= options.merit_tolerance * std::abs(merit0) ||
               -step.slope <= options.merit_tolerance * std::abs(merit0)) {
      // Actual decrease, or the Gauss-Newton model's predicted decrease for this step (-slope is twice
      // it), below the tolerance: further iterations cannot change the merit measurably.
      result.finish(StopCode::MeritTolerance);
      stopped = true;
    }
  }
  if (!stopped && result.stop_reason.empty()) result.finish(cap);
  state.evaluation = std::move(e);
  return result;
}

}  // namespace sd
