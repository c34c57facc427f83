#include "core/solver/methods/arap_method.h"

#include <algorithm>

#include "core/timer.h"

namespace sd {

std::vector<int> ArapMethod::order() const {
  const std::vector<int>& held = energy_->handle_vertices();
  std::vector<int> rows(held.size());
  for (size_t k = 0; k < rows.size(); ++k) rows[k] = static_cast<int>(k);
  std::sort(rows.begin(), rows.end(), [&](int a, int b) { return held[a] < held[b]; });
  return rows;
}

Vertices ArapMethod::targets() const {
  const std::vector<int> rows = order();
  Vertices out(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t r = 0; r < rows.size(); ++r) out.row(static_cast<Eigen::Index>(r)) = energy_->targets().row(rows[r]);
  return out;
}

void ArapMethod::rebuild(const SolverOptions&) {
  if (!solver_) solver_ = std::make_unique<ArapSolver>(mesh_->V, mesh_->F);
  std::vector<int> sorted;
  for (int r : order()) sorted.push_back(energy_->handle_vertices()[static_cast<size_t>(r)]);
  try {
    solver_->set_handles(sorted);
  } catch (...) {
    solver_.reset();  // its state is unknown after a failure: made again next time
    throw;
  }
}

StepResult ArapMethod::run(GaussNewtonState& state, int k, const SolverOptions& options, StopCode cap) {
  prepare(options);
  solver_->set_acceleration(options.arap_acceleration);
  const Vertices pinned = targets();
  const ArapStopTolerances tolerances{options.step_tolerance * energy_->rest_diagonal(), options.arap_energy_tolerance,
                                      options.arap_acceleration > 0};
  const double psi0 = energy_->rest_volume();
  StepResult result;
  for (int i = 0; i < k; ++i) {
    const double t0 = now_ms();
    Vertices X = state.X;
    IterationStats s = solver_->iterate(X, pinned);
    if (!X.allFinite() || !std::isfinite(s.energy)) {
      result.finish(StopCode::NumericalFailure,
                    "numerical failure: the ARAP iterate is not finite; the last good iterate is kept");
      return result;
    }
    s.step = max_row_norm(Eigen::MatrixXd(X - state.X));
    state.X = std::move(X);
    state.evaluation.reset();
    s.iteration = ++state.iteration;
    const Eigen::VectorXd g = energy_->constraints(state.X, &s.volume);
    s.volume_rel_error = (s.volume - psi0) / psi0;
    if (energy_->has_volume_parts()) fill_part_stats(s, g, Eigen::VectorXd(), *energy_);
    s.ms = now_ms() - t0;
    result.iterations.push_back(s);
    if (const std::optional<StopCode> stop = stopping_.after_iteration(s, tolerances)) {
      result.finish(*stop);
      return result;
    }
  }
  result.finish(cap);
  return result;
}

ArapHalfStep ArapMethod::half_step(GaussNewtonState& state, bool local, const SolverOptions& options) {
  prepare(options);
  if (local) return solver_->local_half_step(state.X);
  Vertices X = state.X;
  const ArapHalfStep half = solver_->global_half_step(X, targets());
  state.X = std::move(X);
  state.evaluation.reset();
  stopping_.reset();  // the stopping rule's last energy was of a whole iteration
  return half;
}

}  // namespace sd
