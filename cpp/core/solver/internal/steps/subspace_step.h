// Gauss-Newton steps in the cage subspace X = W P (docs/method.md sections 6, 10 and 11).
// Unknowns: P, m by 3 (column-major; flattened index axis * m + cage vertex in the dense exact mode).
// W acts on x, y, z alike, so the subspace Jacobian is J_f (W (x) I3).
//
//   exact: forms J_f (W (x) I3) densely ((3#V + 3#handles (+ 3 * 7B straightness rows)) by 3m) and solves the 3m by 3m
//          normal equations with a pivoted LDLT each iteration: O(#V m^2), the reference.
//   fast:  the same equations by projected PCG (projected_pcg.h), matrix-free: each product
//          W^T J_f^T J_f W V (V: m by 3) streams W once forward and once transposed. Preconditioner: the constant
//          N = W^T (L^T L + w_pos^2 Phi^T Phi) W (+ the bones' straightness term, w_s^2 (W^T P O)(W^T P O)^T:
//          deformation_energy.h), one m by m matrix shared by x, y and z. Its handle-free
//          part B = (L W)^T (L W) is computed once (O(#V m^2)); a handle or weight change adds the k
//          handle rows and re-factors (O(k m^2 + m^3)). With the option preconditioner 'gauss-newton' (the
//          default), a dense factor of N (x) I3 plus the stiffest vertices' rotation terms where it pays for itself
//          (gauss_newton_factor.h).
// Both modes restore the volume along W N^-1 W^T grad psi (docs/method.md section 8); with volume parts,
// along W N^-1 W^T grad g_k for each part k.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <functional>
#include <memory>

#include "core/solver/internal/constraints/hard_constraints.h"
#include "core/solver/internal/constraints/length_curvature.h"
#include "core/solver/internal/energy/cage_regularization.h"
#include "core/solver/internal/steps/constrained_step.h"
#include "core/solver/internal/steps/gauss_newton_factor.h"
#include "core/solver/internal/steps/lbfgs_preconditioner.h"
#include "core/solver/internal/steps/projected_pcg.h"
#include "core/basis/basis_matrix.h"

namespace sd {

class SubspaceStep : public StepSolver {
 public:
  // Keeps references to energy and W (both must outlive this). Computes B.
  SubspaceStep(const DeformationEnergy& energy, const BasisMatrix& W);

  void refactor(const DeformationEnergy& energy) override;
  ConstrainedStep compute(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                          const Eigen::MatrixXd& U, const SolverOptions& options) override;
  // The cage regularisation R(P) (cage_regularization.h) at its current weight; 0 without one.
  double regularization_energy(const Eigen::MatrixXd& U) const override { return regularization_.energy(U); }
  // Adds the cage regulariser (cage_regularization.h; the cage basis only: a spectral basis has no cage to
  // keep together), forming W^T W once (as costly as B). Its weight follows SolverOptions::cage_regularization
  // at each step (starting from `relative_weight`); N is re-factored when it changes.
  void regularize_cage(const Eigen::MatrixXd& rest_cage, double relative_weight);
  void forget_history() override {
    memory_.clear();
    gauss_newton_.clear();
    restore_du_.resize(0, 0);
    multipliers_.clear();
  }
  // Where the fast steps' factor preconditioner (gauss_newton_factor.h) gets the rotation terms R(U)
  // (factor_rotation_terms.h; 3m x 3m) that it adds to N (x) I3. Without a source (or beyond
  // GaussNewtonFactor::kMaxUnknownsPerAxis, or with the option preconditioner 'constant'), N alone.
  // `vertex_count(exact)` gives the number of units (vertices and clusters, 27 m^2 multiply-adds each) R sums, for
  // the factor's cost; exact only when a factor may pay (finding the stiff vertices costs a pass over W), else at
  // least that number (an upper bound, found without W).
  using MatrixSource = std::function<Eigen::MatrixXd(const Eigen::MatrixXd& U)>;
  using UnitCount = std::function<int(bool exact)>;
  void set_rotation_terms(MatrixSource source, UnitCount vertex_count) {
    rotation_terms_ = std::move(source);
    rotation_vertex_count_ = std::move(vertex_count);
  }
  // The fast steps' base preconditioner at U (docs/method.md section 11.1): the factor of N (x) I3 + R, made
  // now when it pays for itself, or N^-1. The reduced integration's step uses it too. After its PCG run,
  // record_products.
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> base_preconditioner(const Eigen::MatrixXd& U,
                                                                             const SolverOptions& options);
  // `weight`: each product's cost in products over W (1 here; less for a reduced integration's, which passes
  // full_integration false).
  void record_products(int products, double weight = 1.0, bool full_integration = true) {
    gauss_newton_.record(products, weight, full_integration);
  }

  // The last step's multipliers (length_curvature.h), shared with the reduced integration's steps: a drag with
  // reduced integration hands them to the settle with full integration.
  LastMultipliers& multipliers() { return multipliers_; }

  // The pieces, exposed for tests and benchmarks.
  // The products the next full-integration PCG run may spend beyond its start before the factor falls due
  // (GaussNewtonFactor::products_before; unlimited where no factor can be made: option 'constant', no rotation
  // terms, or more than GaussNewtonFactor::kMaxUnknownsPerAxis unknowns per axis).
  int products_before_factor(const SolverOptions& options);
  // W^T J_f^T f: the gradient of E(W P) with respect to P, m by 3.
  Eigen::MatrixXd gradient(const EnergyJacobian& J, const EnergyEvaluation& e) const;
  // The step's right-hand sides from one transposed pass over W (two when 3 + 3Kv > 6 columns): b, the gradient W^T
  // J_f^T f plus the cage regularisation's (m by 3), and c (m by 3 hard.count()) with the volumes' W^T grad psi_k in
  // its first 3Kv columns (the skeleton's are the caller's). Returns the passes. Shared with the reduced integration's
  // finishing steps (reduced_subspace.h).
  int gradients(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X, const Eigen::MatrixXd& U,
                const HardConstraints& hard, Eigen::MatrixXd& b, Eigen::MatrixXd& c) const;
  // J_f (W (x) I3), dense: rows are f's entries (3 * vertex + axis, then 3#V + 3 * handle + axis, then the
  // straightness term's 3#V + 3#handles + axis * 7B + sample), columns axis * m + cage vertex. Throws sd::Error beyond
  // options.exact_memory_budget_bytes.
  Eigen::MatrixXd dense_jacobian(const EnergyJacobian& J, double memory_budget_bytes = 1e9) const;
  // W^T J_f^T J_f W V for a block V (m by 3s); image receives W V. Two passes over W.
  Eigen::MatrixXd product(const EnergyJacobian& J, const Eigen::MatrixXd& V, Eigen::MatrixXd& image) const;
  // N^-1 R for a block R (m by 3s).
  Eigen::MatrixXd precondition(const Eigen::MatrixXd& R) const;
  // What the reduced integration (reduced_subspace.h) shares with this step: the handle rows' Gram matrix
  // H = sum_k w_k^2 W_k^T W_k, plus the bones' straightness term w_s^2 (W^T P O)(W^T P O)^T where it is on (m by m,
  // exact: both terms are quadratic; the latter vanishes at rest, so H (U - U0) is its gradient), the cage
  // regularisation, and
  // applying a changed regularisation weight (re-factoring N).
  const Eigen::MatrixXd& handle_gram() const { return H_; }
  // B = (S L W)^T (S L W), m by m: the Laplacian term's exact square (the rotation clusters' too).
  const Eigen::MatrixXd& laplacian_gram() const { return B_; }
  const CageRegularization& regularization() const { return regularization_; }
  bool factored() const { return factored_; }
  // N (m by m) as a 3m x 3m block-diagonal matrix (index axis * m + j): the base the factor preconditioner's
  // rotation terms are added to. With handle lines (handle_line.h), N (x) I3 less the lines' directions.
  Eigen::MatrixXd constant_matrix() const;
  // The handle vertices' rows of W, each times its weight w_k (#handles by m).
  Eigen::MatrixXd weighted_handle_rows(const DeformationEnergy& energy) const;
  // The handle term's parts along the lines (handle_line.h), sum_k (Wh_k^T Wh_k) (x) (u_k u_k^T), 3m x 3m (index
  // axis * m + j), from the weighted handle rows Wh and the lines' directions u: what the exact matrices and the
  // lines' factor take off the point targets' H (x) I3.
  static Eigen::MatrixXd along_lines_gram(const Eigen::MatrixXd& Wh, const Vertices& u);
  // constant_matrix()^-1 R for a block R (m by 3s): N^-1 per axis, or the lines' factor.
  Eigen::MatrixXd constant_solve(const Eigen::MatrixXd& R) const;
  void sync_options(const SolverOptions& options);
  // The skeleton's points' rows in the subspace, W^T m_q (m by #points; SkeletonConstraints::rows_in, which keeps
  // them with the skeleton); empty without one.
  const Eigen::MatrixXd& skeleton_rows();
  // The unknowns at rest, U0 (X = X0 + W (U - U0)): with them the skeleton's points are q0 + (W^T m_q)^T (U - U0).
  void set_rest_unknowns(const Eigen::MatrixXd& U0) {
    U0_ = U0;
    skeleton_rest_version_ = -1;  // the rest offset is remade
  }
  std::optional<Eigen::MatrixXd> skeleton_points(const Eigen::MatrixXd& U) override;

  double precompute_ms() const { return precompute_ms_; }
  double factor_ms() const { return factor_ms_; }
  // Whether a factor can be made at all (option 'gauss-newton', rotation terms, m <= kMaxUnknownsPerAxis).
  bool factor_wanted(const SolverOptions& options) const;

 private:
  // c: the constraints' right-hand sides, m by 3K; g: their values.
  ConstrainedStep exact_step(const EnergyJacobian& J, const Eigen::MatrixXd& b, const Eigen::MatrixXd& c,
                             const Eigen::VectorXd& g, bool volume, const SolverOptions& options) const;
  // curvature: the bones' lengths' (length_curvature.h), added to A.
  ConstrainedStep fast_step(const EnergyJacobian& J, const Eigen::MatrixXd& U, const Eigen::MatrixXd& b,
                            const Eigen::MatrixXd& c, const Eigen::VectorXd& g, const Eigen::VectorXd& scales,
                            bool volume, const LengthCurvature& curvature, const SolverOptions& options);
  // The factor's cost in products over W with K units in its rotation terms.
  double factor_cost(double K) const;
  // Whether to make the factor now: when the products it could have saved reach its cost (gauss_newton_factor.h).
  bool factor_pays();
  // With handle lines: factors constant_matrix() (3m x 3m) from N and the handle rows Wh (w_k W_k); remade by
  // compute() once the lines have turned (handle_line.h, lines_turned).
  void factor_with_lines(const DeformationEnergy& energy, const Eigen::MatrixXd& Wh);
  // Restores along d (m by 3K), whose image W d is `image` when known (else one pass, when d turned).
  void set_restoration(const Eigen::MatrixXd& d, const Eigen::MatrixXd* image, ConstrainedStep& step);

  const DeformationEnergy* energy_;
  const BasisMatrix* W_;
  CageRegularization regularization_;  // none (eps 0) until regularize_cage
  Eigen::MatrixXd B_;                  // (L W)^T (L W), m by m
  Eigen::MatrixXd H_;                  // sum_h w_h^2 W_h^T W_h (+ the straightness term's, handle_gram())
  Eigen::MatrixXd straightness_rows_;  // w_s W^T P O (m by 7B; no columns without the term), made by refactor()
  Eigen::LLT<Eigen::MatrixXd> N_;      // factor of N = B + H (+ eps P, the regularisation's penalty)
  Eigen::MatrixXd N_matrix_;           // N itself
  bool factored_ = false;
  bool with_lines_ = false;  // lines_N_ serves instead of N (x) I3
  Eigen::LLT<Eigen::MatrixXd> lines_N_;
  Eigen::MatrixXd lines_matrix_;    // what lines_N_ factors
  Eigen::MatrixXd lines_factored_;  // the lines' directions it was made with (remade when they turn)
  LbfgsPreconditioner memory_;      // the base preconditioner updated with the last products' pairs
  GaussNewtonFactor gauss_newton_;  // the base preconditioner where it serves (else N^-1)
  MatrixSource rotation_terms_;
  UnitCount rotation_vertex_count_;
  LastMultipliers multipliers_;  // the last step's, full or reduced integration's: the lengths' curvature
  Eigen::MatrixXd restore_du_;   // the last volume-restoring directions
  std::shared_ptr<const Eigen::MatrixXd> restore_dx_;  // and their images W d
  mutable Eigen::MatrixXd W_dense_;
  Eigen::MatrixXd skeleton_rest_;    // q0 - (W^T m_q)^T U0: the points at U are this + (W^T m_q)^T U
  long skeleton_rest_version_ = -1;  // the energy's skeleton version skeleton_rest_ was made for
  Eigen::MatrixXd U0_;               // empty: the points are mapped from X
  double precompute_ms_ = 0;
  double factor_ms_ = 0;
};

}  // namespace sd
