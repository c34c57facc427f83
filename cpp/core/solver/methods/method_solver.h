// One method of solving (docs/architecture.md, "The solver's methods"): the cage or spectral subspace with full or
// reduced integration (subspace_method.h), the full space (full_space_method.h) or ARAP (arap_method.h). A Deformer
// holds each method it has used and runs the current one; each keeps what it built from the energy and the handles
// (factors, fits), and rebuilds it after it is told they changed.
#pragma once

#include "core/solver/internal/gauss_newton.h"
#include "core/solver/solver_options.h"
#include "core/solver/solver_types.h"

namespace sd {

class MethodSolver {
 public:
  MethodSolver() = default;
  virtual ~MethodSolver() = default;
  // Methods keep references to what they built (callbacks capturing `this`, problems over their own members):
  // held where they were made, never copied or moved.
  MethodSolver(const MethodSolver&) = delete;
  MethodSolver& operator=(const MethodSolver&) = delete;

  // The energy's handles, weights, lines or options changed: what was built from them is rebuilt by prepare().
  void invalidate() { stale_ = true; }
  // Rebuilds now what invalidate() dropped, so that a failure (sd::Error) surfaces in the call that caused it; the
  // method then stays invalid and tries again next time.
  void prepare(const SolverOptions& options) {
    if (!stale_) return;
    rebuild(options);
    stale_ = false;
  }
  // At most k iterations from `state` (updated in place); `cap`: the stop code when they run out. Prepares first.
  virtual StepResult run(GaussNewtonState& state, int k, const SolverOptions& options, StopCode cap) = 0;
  // Forgets what was learned from past iterations (quasi-Newton memories, stopping rules): the next iterations
  // start afresh, as after a reset of the positions.
  virtual void forget_history() {}

 protected:
  virtual void rebuild(const SolverOptions& options) = 0;

 private:
  bool stale_ = true;
};

}  // namespace sd
