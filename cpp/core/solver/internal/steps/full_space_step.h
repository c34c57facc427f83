// Gauss-Newton steps in the full space (docs/method.md section 12): the unknowns are X itself (#V by 3), i.e. the
// subspace step with W = I, for comparison with the cage subspace.
//   exact: the sparse normal equations J_f^T J_f (3#V by 3#V, interleaved) factored by SimplicialLDLT each
//          iteration (the pattern is analysed once).
//   fast:  projected PCG (pcg_step.h, as the subspace's, without its L-BFGS memory, with the bones' lengths'
//          curvature) on the same equations, preconditioned per coordinate by a sparse Cholesky
//          factor of K = L^T L + w_pos^2 Phi^T Phi (#V by #V), factored once per handle or weight change. With handle
//          lines (handle_line.h) a handle vertex's depth is free, which K (pinning it in every direction) misjudges
//          badly: PCG then hit its cap of 50 products per iteration on a capsule. The preconditioner is then K3 =
//          (L^T L) (x) I3 + w_pos^2 Phi^T C Q Phi (3#V by 3#V, interleaved), with the lines' directions when it
//          was factored (once per handle, weight or line change, and when an eye's lines have turned with the
//          targets by more than kPreconditionerTurnDegrees). Where only lines hold the mesh K3 is singular, and K
//          serves.
// The volume is restored along K^-1 grad psi (with volume parts, along K^-1 grad g_k for each part).
// The bones' straightness term (deformation_energy.h) has dense rows, 7B of them: the exact step adds them to its
// sparse factor by the Woodbury identity (three 3#V by 21B dense blocks); K and K3 leave them out, so PCG may take up
// to 21B more products (the full space is the comparison, not the interactive method).
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <memory>

#include "core/solver/internal/constraints/hard_constraints.h"
#include "core/solver/internal/constraints/length_curvature.h"
#include "core/solver/internal/steps/constrained_step.h"

namespace sd {

class FullSpaceStep : public StepSolver {
 public:
  explicit FullSpaceStep(const DeformationEnergy& energy);  // keeps a reference

  void refactor(const DeformationEnergy& energy) override;
  ConstrainedStep compute(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                          const Eigen::MatrixXd& U, const SolverOptions& options) override;

  void forget_history() override { multipliers_.clear(); }

  // J_f^T J_f, 3#V by 3#V interleaved, without the straightness term's dense rows (exact_step adds them by Woodbury).
  Eigen::SparseMatrix<double> normal_matrix(const EnergyJacobian& J) const;

 private:
  // Throws sd::Error (MemoryBudget) when the straightness term's dense blocks would pass memory_budget_bytes.
  void exact_step(const EnergyJacobian& J, const Eigen::MatrixXd& b, const Eigen::MatrixXd& c, const Eigen::VectorXd& g,
                  bool volume, double memory_budget_bytes, ConstrainedStep& step);
  // Projected PCG (pcg_step.h) preconditioned by K (or K3), with the bones' lengths' curvature (length_curvature.h).
  ConstrainedStep fast_step(const EnergyJacobian& J, const EnergyEvaluation& e, const HardConstraints& hard,
                            const Eigen::MatrixXd& b, const Eigen::MatrixXd& c, const Eigen::VectorXd& g,
                            const SolverOptions& options) const;

  const DeformationEnergy* energy_;
  // K^-1 (or K3^-1 with lines) applied to a block of #V by 3s.
  Eigen::MatrixXd precondition(const Eigen::MatrixXd& R) const;

  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> K_;   // null without handles
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> K3_;  // with handle lines
  Eigen::MatrixXd lines_factored_;  // the lines' directions K3 was made with (remade when they turn)
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> H_;  // exact mode; pattern analysed once
  bool analysed_ = false;
  LastMultipliers multipliers_;  // the last step's: the fast steps' lengths' curvature (length_curvature.h)
};

}  // namespace sd
