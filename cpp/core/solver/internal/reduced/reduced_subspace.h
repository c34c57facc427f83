// The subspace problem with reduced integration (docs/method.md section 17): the same unknowns, constraints and
// handle term as the subspace step (subspace_step.h), with the Laplacian term computed by a reduced rule
// (reduced_laplacian_term.h: sampled vertices, or rotation clusters) instead of over every vertex:
//   E(U) = E_rule(U) + 1/2 sum_k w_pos^2 c_k |x_k - v_k|^2 + E_s(U) + R(U),   X = X0 + W (U - U0),
// E_s the bones' straightness term (deformation_energy.h), exact and quadratic like the handle term, so that both are
// the subspace step's one m x m matrix H (handle_gram()) and its gradient H (U - U0) less the targets' pull.
// What an iteration costs no longer grows with the mesh beyond two passes over W:
//   - the rule's value, gradient and Gauss-Newton products need no pass over W;
//   - the handle term and the volume constraints stay exact: the handle term's gradient reads the handles' rows
//     of W, one forward pass maps the step and the restoring direction to X, and the line search evaluates the
//     volume and the handles at X + alpha dx (O(#V) arithmetic, no further pass over W);
//   - the constraint's gradient in U, c = W^T grad psi(X), is one transposed pass (a quadrature of it at the
//     clusters' centres was tried: its error stalled solves short of the minimum, docs/method.md section 17).
//     While the handles move, the last pass's c serves the frames in which the mesh's volume gradients turned
//     little since it was made (volume_directions); at rest every iteration makes it anew.
// The step is the subspace step's (constrained_step.h) with A, b replaced by the rule's; the fast mode runs the
// same projected PCG, preconditioned as the subspace step is (its N and rotation terms are the full Laplacian
// term's, which the rule approximates); the exact mode forms the 3m x 3m matrix.
// Restoration is along W N^-1 c_k, as in the subspace step's exact mode.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <functional>
#include <vector>

#include "core/solver/internal/constraints/hard_constraints.h"
#include "core/solver/internal/reduced/reduced_laplacian_term.h"
#include "core/solver/internal/gauss_newton.h"
#include "core/solver/internal/steps/lbfgs_preconditioner.h"
#include "core/solver/internal/steps/subspace_step.h"

namespace sd {

class ReducedSubspace : public Objective {
 public:
  // Keeps references to energy, W and the subspace step (which must outlive this; the step provides N, H and the
  // regularisation and must be factored for the current handles before step() is called).
  ReducedSubspace(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                  SubspaceStep& subspace, std::unique_ptr<ReducedLaplacianTerm> rule);

  const DeformationEnergy& energy() const override { return *energy_; }
  EnergyEvaluation evaluate(const Vertices& X, const Eigen::MatrixXd& U) const override;
  void update_position_terms(const Vertices& X, EnergyEvaluation& e) const override {
    energy_->update_position_terms(X, e);
  }
  ConstrainedStep step(const EnergyEvaluation& e, const Vertices& X, const Eigen::MatrixXd& U,
                       const SolverOptions& options) override;
  double regularization_energy(const Eigen::MatrixXd& U) const override { return subspace_->regularization_energy(U); }
  // A finishing step (docs/method.md section 17.3; finishing_integration.h): the gradient b and the volumes' c of the
  // energy summed over every vertex (J and e evaluated at X on the whole mesh, one transposed pass over W), with the
  // rule's Gauss-Newton matrix A. Its fixed points are the full integration's: only the matrix is approximate.
  ConstrainedStep finishing_step(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                                 const Eigen::MatrixXd& U, const SolverOptions& options);
  void forget_history() {
    memory_.clear();
    restore_du_.resize(0, 0);
    volume_c_gradients_.resize(0, 0);
  }

  // The pieces, for tests and benchmarks. linearize() sets the point of gradient(), product() and dense_matrix().
  void linearize(const Eigen::MatrixXd& U);
  // The gradient of E in U at the linearised point U, for an evaluation there: m by 3.
  Eigen::MatrixXd gradient(const EnergyEvaluation& e, const Eigen::MatrixXd& U);
  // A V (m by 3s): the Gauss-Newton matrix of E (the rule's Laplacian term, exact handle term and regularisation).
  Eigen::MatrixXd product(const Eigen::MatrixXd& V) const;
  // The same as a dense 3m x 3m matrix (index axis * m + j), the exact mode's.
  Eigen::MatrixXd dense_matrix() const;
  int sample_count() const { return rule_->sample_count(); }
  // How far the volume constraints' gradients over the mesh may turn during a drag before a frame makes c anew
  // (volume_directions): the largest over the constraints of |grad psi_k(X) - grad psi_k(X_c)| / |grad psi_k(X_c)|.
  static constexpr double kLaggedTilt = 0.05;

 private:
  // The handle term's gradient in U, with the straightness term's (part of H): H U - G.
  Eigen::MatrixXd handle_gradient(const Eigen::MatrixXd& U);
  // The handle lines' part of the handle term (handle_line.h), to be taken off the point targets' one:
  // sum_k w_k^2 W_k^T ((o_k . u_k) u_k) with o_k = offset(k, W_k V) (m by 3; V is m by 3).
  Eigen::MatrixXd along_lines(const std::function<Eigen::RowVector3d(Eigen::Index, const Eigen::RowVector3d&)>& offset,
                              const Eigen::MatrixXd& V) const;
  // G (below) for the current targets and weights, remaking only the parts of the groups that changed.
  void update_handle_pull();
  // The volume constraints' c = W^T grad psi(X) for a step at X: the kept one where `may_lag` (a fast step of a
  // drag: the targets changed since the last step) and grad psi turned by at most kLaggedTilt since it was made,
  // else made anew by one transposed pass (made: true). Why: that pass is a third of a reduced drag frame, and c
  // changes only as the mesh's area normals turn; restoration still keeps the volume exact. At rest (the same
  // targets) every step makes it, so a solve converges where it did with c made every time.
  const Eigen::MatrixXd& volume_directions(const Vertices& X, bool may_lag, bool& made);
  ConstrainedStep exact_step(const Eigen::MatrixXd& b, const Eigen::MatrixXd& c, const Eigen::VectorXd& g,
                             bool volume) const;
  // The step for gradient b and the volumes' c (m by 3K; the skeleton's columns are filled here), with A at the
  // linearised point, and its forward map: what step() and finishing_step() share.
  ConstrainedStep solve_step(const EnergyEvaluation& e, const Eigen::MatrixXd& U, const Eigen::MatrixXd& b,
                             Eigen::MatrixXd& c, const HardConstraints& hard, const SolverOptions& options);

  const DeformationEnergy* energy_;
  const BasisMatrix* W_;
  Eigen::MatrixXd U0_;
  SubspaceStep* subspace_;
  std::unique_ptr<ReducedLaplacianTerm> rule_;
  // The handle term's gradient is H U - G with G = sum_k w_k^2 W_k^T v_k (v_k the targets): per group, one
  // product with its rows of W when its targets (or weights) change, then m x m work per iteration. A drag moves
  // one group per frame, so the fixed groups' parts are kept.
  std::vector<int> handle_rows_;           // the handle vertices, groups in order
  std::vector<int> group_sizes_;           // of those groups
  std::vector<BasisMatrix> W_groups_;      // each group's rows of W
  std::vector<Eigen::MatrixXd> G_groups_;  // each group's part of G (empty: to be made)
  Eigen::MatrixXd pulled_;                 // the rows w_k^2 (v_k - x0_k) the parts were made from
  Eigen::MatrixXd G_;
  long G_version_ = -1;
  LbfgsPreconditioner memory_;
  Eigen::MatrixXd restore_du_;                         // the last restoring directions
  std::shared_ptr<const Eigen::MatrixXd> restore_dx_;  // and their images W d
  Eigen::MatrixXd volume_c_;                           // the volume constraints' c from the last transposed pass
  Eigen::MatrixXd volume_c_gradients_;                 // grad psi it was made from (#V by 3K; none: to be made)
  long volume_c_parts_ = -1;                           // and the energy's volume_parts_version then
  Vertices last_step_targets_;                         // the targets of the last step (another: a drag's frame)
};

}  // namespace sd
