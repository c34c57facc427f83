// The subspace method (docs/method.md sections 6-11 and 17): Gauss-Newton over the coefficients U of a basis W (a
// cage's coordinates or the spectral basis), X = X0 + W (U - U0), with the energy summed over every vertex (full
// integration: subspace_step.h) or by a reduced rule (reduced integration: reduced_subspace.h). It owns what the
// subspace steps build from the energy: the step solver with its constant preconditioner, the stiffest vertices
// and the rotation terms of the fast steps' factor, and the reduced integration's rule, made on first use and
// kept until the energy's weighting changes (a Deformer then makes a new SubspaceMethod). The rule: every vertex
// (exact) on a mesh of at most max(800, 2m) vertices; on larger ones that many rotation clusters
// (rotation_clusters.h), measured on held-out poses.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "core/basis/basis_matrix.h"
#include "core/solver/internal/reduced/reduced_subspace.h"
#include "core/solver/internal/steps/factor_rotation_terms.h"
#include "core/solver/internal/steps/subspace_step.h"
#include "core/solver/methods/method_solver.h"

namespace sd {

class SubspaceMethod : public MethodSolver {
 public:
  // Keeps references to the energy, W and U0 (which must outlive this); computes the step's constant matrix
  // (O(#V m^2)). A cage (cage_regularization > 0 allowed) gets the cage regulariser; the spectral basis none.
  SubspaceMethod(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0, bool cage,
                 double cage_regularization);

  StepResult run(GaussNewtonState& state, int k, const SolverOptions& options, StopCode cap) override;
  void forget_history() override;

  // What the reduced integration's rule is, once it is made.
  struct ReducedRule {
    bool clusters = false;  // rotation clusters; else every vertex, summed exactly
    int samples = 0;        // the vertices it reads: every one, or the clusters' centres
    int candidates = 0;     // the mesh's vertices
    double test_error = 0;  // cluster_test_error on eight held-out poses (0 for the exact sum)
    double ms = 0;          // time to make it
  };
  // Makes the rule now if it was not (prepare_reduced: the app makes it before a drag).
  const ReducedRule& prepare_reduced();
  const std::optional<ReducedRule>& reduced_rule() const { return rule_; }
  // Makes the factor preconditioner's parts that depend on no pose now, if `options` would let the fast steps buy it
  // and they were not made: the stiffest vertices and the rotation clusters (factor_rotation_terms.h; 0.2 to 0.5 s on
  // a 40k-vertex mesh in a 391-vertex cage). The first solve that buys the factor then pays only for the pose's terms
  // and the Cholesky factor; the app makes them after a model loads, before the first settle needs them.
  void prepare_factor(const SolverOptions& options);
  bool factor_prepared() const { return rotation_terms_ != nullptr; }
  double regularization_energy(const Eigen::MatrixXd& U) const { return step_->regularization_energy(U); }
  double precompute_ms() const { return step_->precompute_ms(); }

 protected:
  void rebuild(const SolverOptions&) override {
    step_->refactor(*energy_);                 // forgets its own history: its pairs belong to the old A
    if (reduced_) reduced_->forget_history();  // so do the reduced problem's
    rule_converged_.reset();                   // the handles, weights or options changed: the rule's solve starts again
  }

 private:
  // Which energy the last reduced iterations minimised (a switch drops the state's evaluation).
  enum class Phase { Rule, Finishing };
  // Where the rule's iterations converged or stalled (or full integration's converged): the finishing iterations go
  // on while the problem is the same.
  struct ConvergedAt {
    Vertices targets;
    long skeleton_version = 0;
    long volume_parts_version = 0;
    int finishing_steps = 0;  // taken with the rule's matrix since
    double last_step = 0;     // the last finishing iteration's proposed step length (0: none yet)
  };
  const std::vector<int>& stiff();
  FactorRotationTerms& factor_terms();  // made on first use
  // The units (stiff vertices and clusters) of the factor's rotation terms, for its price; `exact`: found, not bounded.
  int factor_units(bool exact);
  ReducedSubspace& reduced();
  // Whether the rule's iterations have converged for the current problem (targets compared by value: an app may send
  // the same ones again).
  bool finishing() const;
  void enter(Phase phase, GaussNewtonState& state);
  // Remembers the current problem as converged, with this many finishing steps by the rule's matrix already taken.
  void converged_here(int finishing_steps);
  // The finishing iterations: at most kFinishingSteps with the rule's matrix (finishing_integration.h; none where the
  // rule failed its test), then full integration's steps.
  StepResult finish_reduced(GaussNewtonState& state, int k, const SolverOptions& options, StopCode cap);

  const DeformationEnergy* energy_;
  const BasisMatrix* W_;
  const Eigen::MatrixXd* U0_;
  std::unique_ptr<SubspaceStep> step_;
  std::optional<std::vector<int>> stiff_;                // vertex_stiffness.h, found on first use
  std::unique_ptr<FactorRotationTerms> rotation_terms_;  // at those vertices and in clusters, made on first use
  std::optional<ReducedRule> rule_;                      // what reduced_'s rule is
  std::unique_ptr<ReducedSubspace> reduced_;             // the reduced problem over step_, made on first use
  std::optional<ConvergedAt> rule_converged_;
  Phase phase_ = Phase::Rule;
};

}  // namespace sd
