#include "core/solver/internal/steps/full_space_step.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel/solve_columns.h"
#include "core/solver/internal/constraints/hard_constraints.h"
#include "core/solver/internal/constraints/length_curvature.h"
#include "core/solver/internal/steps/pcg_step.h"
#include "core/solver/internal/steps/projected_pcg.h"

namespace sd {

namespace {

// K3 = (L^T L) (x) I3 + the handle rows' w^2 Q (full_space_step.h), factored.
std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> lines_preconditioner(
    const DeformationEnergy& energy) {
  const Eigen::SparseMatrix<double> LtL = energy.laplacian().transpose() * energy.laplacian();
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < LtL.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(LtL, j); it; ++it)
      for (int a = 0; a < 3; ++a)
        entries.emplace_back(3 * static_cast<int>(it.row()) + a, 3 * static_cast<int>(it.col()) + a, it.value());
  const Eigen::VectorXd& w = energy.handle_row_weights();
  const auto& handles = energy.handle_vertices();
  for (size_t k = 0; k < handles.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    for (int a = 0; a < 3; ++a) {
      const Eigen::RowVector3d q = energy.across_line(row, Eigen::RowVector3d::Unit(a));
      for (int b = 0; b < 3; ++b) entries.emplace_back(3 * handles[k] + a, 3 * handles[k] + b, w[row] * w[row] * q[b]);
    }
  }
  const int n = 3 * energy.vertex_count();
  Eigen::SparseMatrix<double> K3(n, n);
  K3.setFromTriplets(entries.begin(), entries.end());
  auto factor = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(K3);
  // Only lines hold the mesh (every handle's depth free along one direction: K3 is singular): K still serves.
  const Eigen::VectorXd D = factor->info() == Eigen::Success ? Eigen::VectorXd(factor->vectorD()) : Eigen::VectorXd();
  if (D.size() == 0 || !D.allFinite() || !(D.minCoeff() > 1e-10 * D.cwiseAbs().maxCoeff())) return nullptr;
  return factor;
}

// The straightness term's rows as columns of the interleaved 3#V space: w_s (P O) (x) I3, 3#V by 3 * 7B (column
// 3s + a is sample s's offset along axis a).
Eigen::MatrixXd straightness_columns(const DeformationEnergy& energy) {
  const Eigen::MatrixXd& R = energy.skeleton()->offset_rows();
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(3 * R.rows(), 3 * R.cols());
  for (Eigen::Index s = 0; s < R.cols(); ++s)
    for (int a = 0; a < 3; ++a)
      for (Eigen::Index i = 0; i < R.rows(); ++i) Z(3 * i + a, 3 * s + a) = energy.straightness_weight() * R(i, s);
  return Z;
}

// The straightness term's Woodbury solve holds Z and H^-1 Z, two 3#V x 21B dense blocks at once: refused beyond the
// exact mode's memory budget, as the subspace's dense Jacobian is.
void check_low_rank_budget(const DeformationEnergy& energy, double memory_budget_bytes) {
  const double rows = 3.0 * energy.vertex_count(), columns = 3.0 * energy.skeleton()->offset_rows().cols();
  const double bytes = 2.0 * 8.0 * rows * columns;
  if (bytes <= memory_budget_bytes) return;
  std::ostringstream message;
  message << "exact mode needs " << static_cast<long long>(bytes / 1e6) << " MB for the bones' straightness term ("
          << static_cast<long long>(rows) << " x " << static_cast<long long>(columns)
          << " dense columns, twice), more than the budget of " << static_cast<long long>(memory_budget_bytes / 1e6)
          << " MB; use the fast mode, fewer bones or straightnessWeight 0";
  throw Error(ErrorCode::MemoryBudget, message.str());
}

// (H + Z Z^T)^-1 Y from H^-1 (Woodbury): H^-1 Y - H^-1 Z (I + Z^T H^-1 Z)^-1 Z^T H^-1 Y. Z has few columns (the
// straightness term's), so the sparse factor of H serves the dense low-rank term.
template <typename Solve>
Eigen::MatrixXd solve_with_low_rank(const Solve& solve, const Eigen::MatrixXd& Z, const Eigen::MatrixXd& Y) {
  const Eigen::MatrixXd HY = solve(Y), HZ = solve(Z);
  const Eigen::MatrixXd small = Eigen::MatrixXd::Identity(Z.cols(), Z.cols()) + Z.transpose() * HZ;
  return HY - HZ * small.ldlt().solve(Z.transpose() * HY);
}

}  // namespace

FullSpaceStep::FullSpaceStep(const DeformationEnergy& energy) : energy_(&energy) {}

void FullSpaceStep::refactor(const DeformationEnergy& energy) {
  multipliers_.clear();                    // a new handle set: a new problem
  if (energy.handle_vertices().empty()) {  // K = L^T L is singular (L 1 = 0)
    K_.reset();
    return;
  }
  auto factor = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(energy.constant_normal_matrix());
  if (factor->info() != Eigen::Success)
    throw Error(ErrorCode::NumericalFailure,
                "full space: the preconditioner L^T L + w^2 Phi^T Phi could not be factored (" +
                    std::to_string(energy.vertex_count()) + " vertices); is the position weight positive?");
  K_ = std::move(factor);
  K3_.reset();
  lines_factored_ = energy.line_directions();
  if (energy.has_handle_lines()) K3_ = lines_preconditioner(energy);
}

Eigen::MatrixXd FullSpaceStep::precondition(const Eigen::MatrixXd& R) const {
  if (!K3_) return parallel::solve_columns(*K_, R);
  return deinterleave(parallel::solve_columns(*K3_, interleave(R)));
}

Eigen::SparseMatrix<double> FullSpaceStep::normal_matrix(const EnergyJacobian& J) const {
  const Eigen::SparseMatrix<double> M = J.laplacian_rows_matrix();  // L (x) I3 - J_delta_hat
  Eigen::SparseMatrix<double> H = M.transpose() * M;
  const Eigen::VectorXd& w = energy_->handle_row_weights();
  const auto& handles = energy_->handle_vertices();
  // Each handle vertex adds w^2 Q to its 3x3 diagonal block (Q = I for a point target; M^T M fills the block).
  for (size_t k = 0; k < handles.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    for (int a = 0; a < 3; ++a) {
      const Eigen::RowVector3d q = energy_->across_line(row, Eigen::RowVector3d::Unit(a));
      for (int b = 0; b < 3; ++b)
        if (q[b] != 0.0) H.coeffRef(3 * handles[k] + a, 3 * handles[k] + b) += w[row] * w[row] * q[b];
    }
  }
  H.makeCompressed();
  return H;
}

void FullSpaceStep::exact_step(const EnergyJacobian& J, const Eigen::MatrixXd& b, const Eigen::MatrixXd& c,
                               const Eigen::VectorXd& g, bool volume, double memory_budget_bytes,
                               ConstrainedStep& step) {
  if (energy_->has_straightness_term()) check_low_rank_budget(*energy_, memory_budget_bytes);
  Eigen::SparseMatrix<double> H = normal_matrix(J);
  // A relative 1e-12 shift keeps the factorization defined where J_f^T J_f is only semidefinite (a single
  // handle vertex at rest leaves a rotation free); it changes the step by about that much.
  const double shift = 1e-12 * H.diagonal().cwiseAbs().mean();
  for (Eigen::Index i = 0; i < H.rows(); ++i) H.coeffRef(i, i) += shift;
  if (!analysed_) {
    H_.analyzePattern(H);
    analysed_ = true;
  }
  H_.factorize(H);
  if (H_.info() != Eigen::Success)
    throw Error(ErrorCode::NumericalFailure, "exact full-space step: J_f^T J_f could not be factored");
  const Eigen::Index K = c.cols() / 3;
  Eigen::MatrixXd rhs(H.rows(), volume ? 1 + K : 1);
  rhs.col(0) = interleave(b);
  if (volume) rhs.rightCols(K) = interleave(c);
  // The straightness term's dense rows are not in the sparse H: they join by the Woodbury identity.
  const auto solve = [&](const Eigen::MatrixXd& Y) { return Eigen::MatrixXd(H_.solve(Y)); };
  const Eigen::MatrixXd sol =
      energy_->has_straightness_term() ? solve_with_low_rank(solve, straightness_columns(*energy_), rhs) : solve(rhs);
  const Eigen::MatrixXd u = deinterleave(sol.col(0));
  const Eigen::MatrixXd V = volume ? Eigen::MatrixXd(deinterleave(sol.rightCols(K))) : Eigen::MatrixXd();
  step.lambda = volume ? volume_multipliers(u, V, c, g) : Eigen::VectorXd(Eigen::VectorXd::Zero(K));
  step.du = volume ? Eigen::MatrixXd(-add_blocks(u, V, step.lambda)) : Eigen::MatrixXd(-u);
  step.slope = block_dot(step.du, add_blocks(b, c, step.lambda));
}

ConstrainedStep FullSpaceStep::fast_step(const EnergyJacobian& J, const EnergyEvaluation& e,
                                         const HardConstraints& hard, const Eigen::MatrixXd& b,
                                         const Eigen::MatrixXd& c, const Eigen::VectorXd& g,
                                         const SolverOptions& options) const {
  PcgStepProblem problem;
  problem.product = [&](const Eigen::MatrixXd& P, Eigen::MatrixXd& image) {
    image = P;  // no W here: the "image" of a block is the block itself
    return Eigen::MatrixXd(J.normal_product(P));
  };
  // x, y and z solve with the one factor of K side by side (parallel::solve_columns), or K3 with lines.
  problem.base_preconditioner = [&](const Eigen::MatrixXd& R) { return precondition(R); };
  problem.image_rows = b.rows();
  // Without a skeleton the energy has no point rows to give.
  std::optional<LengthCurvature> curvature;
  if (hard.skeleton_count() > 0) {
    curvature.emplace(hard, e, energy_->skeleton()->point_rows(), multipliers_);
    problem.curvature = curvature->term();
  }
  // K is exact for the Laplacian's linear part: the full space keeps no L-BFGS memory.
  SolverOptions without_memory = options;
  without_memory.cg_memory = 0;
  LbfgsPreconditioner memory;
  std::unique_ptr<ProjectedPcg> pcg;
  return pcg_step(problem, memory, b, c, g, hard.scales(), !hard.empty(), without_memory, pcg);
}

ConstrainedStep FullSpaceStep::compute(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                                       const Eigen::MatrixXd& /*U = X*/, const SolverOptions& options) {
  if (!K_) throw Error("full space: no handles are set, so the step is undefined");
  // An eye's lines turn with the targets: K3 is remade past kPreconditionerTurnDegrees (K stays).
  if (energy_->has_handle_lines() && lines_turned(lines_factored_, energy_->line_directions())) {
    lines_factored_ = energy_->line_directions();
    K3_ = lines_preconditioner(*energy_);
  }
  const HardConstraints hard(*energy_, options.volume);
  const bool volume = !hard.empty();  // any hard constraint: the volume's or the skeleton's
  const Eigen::Index n = X.rows();
  const Eigen::Index K = hard.count();
  const Eigen::MatrixXd b = J.gradient(e);
  Eigen::MatrixXd c(n, 3 * K);
  c.leftCols(3 * hard.volume_count()) = hard.volume_gradients(X);
  if (hard.skeleton_count() > 0)
    c.rightCols(3 * hard.skeleton_count()) = hard.skeleton_gradients(e, energy_->skeleton()->point_rows());
  const Eigen::VectorXd g = hard.values(e);
  ConstrainedStep step;
  if (options.jacobian == JacobianMode::Exact) {
    exact_step(J, b, c, g, volume, options.exact_memory_budget_bytes, step);
  } else {
    step = fast_step(J, e, hard, b, c, g, options);
  }
  multipliers_.keep(step.lambda, energy_->skeleton_version());
  step.dx = step.du;
  if (volume) {
    step.restore.du = precondition(c);
    step.restore.dx = std::make_shared<const Eigen::MatrixXd>(step.restore.du);
    if (hard.skeleton_count() > 0)
      step.restore.point_motion = energy_->skeleton()->point_rows().transpose() * step.restore.du;
  }
  return step;
}

}  // namespace sd
