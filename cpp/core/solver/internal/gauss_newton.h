// The outer loop of the constrained Gauss-Newton solver (docs/method.md sections 6-9):
//   1. the step h and multipliers lambda from a StepSolver (docs/method.md section 6);
//   2. Armijo backtracking on the merit 1/2 |f|^2 + lambda . g (docs/method.md section 7): accept alpha when
//      merit(X + alpha dx) <= merit(X) + c1 alpha slope, else alpha <- c2 alpha;
//   3. volume restoration (volume_restoration.h): Newton steps on psi(X + t r) = psi(X0) along the solver's
//      restoration direction r (W N^-1 W^T grad psi), or on the K part volumes along K directions, so the hard
//      constraints stay hard when alpha < 1;
//   4. stop when the step is below step_tolerance x the rest bounding-box diagonal, when the merit stops
//      decreasing (the actual or the model-predicted decrease below merit_tolerance relative; an iterate
//      that would raise the merit is not taken), or at the iteration cap. "The merit stopped decreasing" is a
//      convergence only at a stationary point of the Gauss-Newton model; elsewhere it is StopCode::Stalled.
// Each iteration's stats record the line search (every trial's alpha and merit) for stepping through a solve.
// Never produces NaN or Inf: a non-finite energy, step or multiplier keeps the last good iterate and
// reports StopCode::NumericalFailure.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "core/solver/internal/steps/constrained_step.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/constraints/volume_restoration.h"
#include "core/solver/solver_types.h"

namespace sd {

struct GaussNewtonState {
  Vertices X;         // current positions, #V by 3
  Eigen::MatrixXd U;  // current unknowns (P for the subspace, X for the full space)
  int iteration = 0;  // iterations since the last reset
  // The energy at X as the last gauss_newton call left it, so the next call (an interactive frame: the
  // targets moved, X did not) only updates the handle terms instead of evaluating the whole mesh again.
  // Whoever changes X otherwise must clear it.
  std::optional<EnergyEvaluation> evaluation;
  // The restoring directions of the nonlinear constraints, kept while the step solver keeps its own.
  NonlinearRestoration restoration;
};

// What the loop minimises, at points (X, U): the mesh and the unknowns (U = P, the subspace coefficients, with
// X = X0 + W (U - U0); or U = X in the full space). The loop moves both along the step and never forms one from
// the other itself, so an objective may evaluate the energy from either: FullIntegration from X (every vertex),
// ReducedSubspace (reduced_subspace.h) its Laplacian term from U at a few sampled vertices.
class Objective {
 public:
  virtual ~Objective() = default;
  virtual const DeformationEnergy& energy() const = 0;
  // The energy and the constraints at (X, U).
  virtual EnergyEvaluation evaluate(const Vertices& X, const Eigen::MatrixXd& U) const = 0;
  // e, evaluated at (X, U), with its handle terms recomputed (the targets or the weight changed since).
  virtual void update_position_terms(const Vertices& X, EnergyEvaluation& e) const = 0;
  // The constrained Gauss-Newton step at (X, U), where e was evaluated.
  virtual ConstrainedStep step(const EnergyEvaluation& e, const Vertices& X, const Eigen::MatrixXd& U,
                               const SolverOptions& options) = 0;
  // The regularisation of the unknowns that the merit includes (StepSolver::regularization_energy).
  virtual double regularization_energy(const Eigen::MatrixXd& U) const = 0;
};

// The energy summed over every vertex, with the step of a StepSolver (subspace or full space).
class FullIntegration : public Objective {
 public:
  // Keeps references to both.
  FullIntegration(const DeformationEnergy& energy, StepSolver& steps) : energy_(&energy), steps_(&steps) {}
  const DeformationEnergy& energy() const override { return *energy_; }
  EnergyEvaluation evaluate(const Vertices& X, const Eigen::MatrixXd& U) const override {
    return energy_->evaluate(X, steps_->skeleton_points(U));
  }
  void update_position_terms(const Vertices& X, EnergyEvaluation& e) const override {
    energy_->update_position_terms(X, e);
  }
  ConstrainedStep step(const EnergyEvaluation& e, const Vertices& X, const Eigen::MatrixXd& U,
                       const SolverOptions& options) override;
  double regularization_energy(const Eigen::MatrixXd& U) const override { return steps_->regularization_energy(U); }

 protected:
  // The energy's Jacobian at X (every vertex).
  const EnergyJacobian& jacobian_at(const Vertices& X);

 private:
  const DeformationEnergy* energy_;
  StepSolver* steps_;
  std::optional<EnergyJacobian> J_;  // kept across iterations so its sparse storage is reused
};

// Runs at most `max_iterations` iterations from `state` (updated in place). `cap` is the stop code
// used when the cap is reached without convergence (IterationLimit or MaxIterations).
StepResult gauss_newton(Objective& objective, GaussNewtonState& state, int max_iterations, const SolverOptions& options,
                        StopCode cap);
// The same on the full energy with a step solver.
StepResult gauss_newton(const DeformationEnergy& energy, StepSolver& steps, GaussNewtonState& state, int max_iterations,
                        const SolverOptions& options, StopCode cap);

// The per-part statistics (volume parts only): part_volume_change[k] = g_k / |V_k(X0)| and part_lambda =
// lambda (empty lambda, e.g. ARAP: zeros).
void fill_part_stats(IterationStats& s, const Eigen::VectorXd& g, const Eigen::VectorXd& lambda,
                     const DeformationEnergy& energy);

}  // namespace sd
