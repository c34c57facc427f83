// The end of a reduced solve (docs/method.md section 17.3): Gauss-Newton iterations on the energy summed over every
// vertex, each step taken with the reduced rule's Gauss-Newton matrix.
//
// Why: the rule's minimiser lies 2e-3 to 3e-3 of the diagonal from the full integration's on real models in their
// own cages, and no cheaper rule came closer (the first-order error of one rotation per cluster). Its matrix, though,
// is a good model of the full one. So once the rule's iterations have converged, these iterations take the exact
// gradient (one transposed pass over W, and the nonlinear terms at every vertex) and solve the rule's system for the
// step (products without W), so that their fixed points are the full integration's. Only the matrix is approximate,
// so they converge linearly: the first steps took roughly half of the distance to the full shape off each on those
// models, the spiky box's only 13% per step. The merit is the full one, so the line search, restoration and stop
// codes mean what they mean in full integration.
#pragma once

#include "core/solver/internal/gauss_newton.h"
#include "core/solver/internal/reduced/reduced_subspace.h"
#include "core/solver/internal/steps/subspace_step.h"

namespace sd {

// The full integration's energy, evaluation and merit (FullIntegration over the subspace step), with the step of
// ReducedSubspace::finishing_step.
class FinishingIntegration : public FullIntegration {
 public:
  // Keeps references to all three (the reduced problem and the subspace step it was made over).
  FinishingIntegration(const DeformationEnergy& energy, SubspaceStep& subspace, ReducedSubspace& reduced)
      : FullIntegration(energy, subspace), reduced_(&reduced) {}
  ConstrainedStep step(const EnergyEvaluation& e, const Vertices& X, const Eigen::MatrixXd& U,
                       const SolverOptions& options) override {
    return reduced_->finishing_step(jacobian_at(X), e, X, U, options);
  }

 private:
  ReducedSubspace* reduced_;
};

}  // namespace sd
