// The full-space method (docs/method.md section 9): Gauss-Newton over every vertex position, each step by the
// full-space step solver (full_space_step.h).
#pragma once

#include "core/solver/internal/steps/full_space_step.h"
#include "core/solver/methods/method_solver.h"

namespace sd {

class FullSpaceMethod : public MethodSolver {
 public:
  // Keeps a reference to the energy, which must outlive this.
  explicit FullSpaceMethod(const DeformationEnergy& energy) : energy_(&energy), steps_(energy) {}
  StepResult run(GaussNewtonState& state, int k, const SolverOptions& options, StopCode cap) override {
    prepare(options);
    return gauss_newton(*energy_, steps_, state, k, options, cap);
  }

 protected:
  void rebuild(const SolverOptions&) override { steps_.refactor(*energy_); }

 private:
  const DeformationEnergy* energy_;
  FullSpaceStep steps_;
};

}  // namespace sd
