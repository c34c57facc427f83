#include "core/full_space_step.h"

#include <string>
#include <vector>

#include "core/batched_pcg.h"
#include "core/error.h"

namespace sd {
namespace {

Eigen::SparseMatrix<double> kron_identity3(const Eigen::SparseMatrix<double>& L) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(L.nonZeros()) * 3);
  for (Eigen::Index col = 0; col < L.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it)
      for (int a = 0; a < 3; ++a) entries.emplace_back(3 * it.row() + a, 3 * col + a, it.value());
  Eigen::SparseMatrix<double> out(3 * L.rows(), 3 * L.cols());
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

}  // namespace

FullSpaceStep::FullSpaceStep(const DeformationEnergy& energy)
    : energy_(&energy), LI3_(kron_identity3(energy.laplacian())) {}

void FullSpaceStep::refactor(const DeformationEnergy& energy) {
  if (energy.handle_vertices().empty()) {  // K = L^T L is singular (L 1 = 0)
    K_.reset();
    return;
  }
  auto factor = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(energy.constant_normal_matrix());
  if (factor->info() != Eigen::Success)
    throw Error("full space: the preconditioner L^T L + w^2 Phi^T Phi could not be factored (" +
                std::to_string(energy.vertex_count()) + " vertices); is the position weight positive?");
  K_ = std::move(factor);
}

Eigen::SparseMatrix<double> FullSpaceStep::normal_matrix(const EnergyJacobian& J) const {
  const Eigen::SparseMatrix<double> M = LI3_ - J.delta_hat_jacobian();
  Eigen::SparseMatrix<double> H = M.transpose() * M;
  const double w2 = energy_->position_weight() * energy_->position_weight();
  for (int v : energy_->handle_vertices())
    for (int a = 0; a < 3; ++a) H.coeffRef(3 * v + a, 3 * v + a) += w2;
  H.makeCompressed();
  return H;
}

ConstrainedStep FullSpaceStep::compute(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                                       const SolverOptions& options) {
  if (!K_) throw Error("full space: no handles are set, so the step is undefined");
  const bool volume = options.volume;
  const Eigen::Index n = X.rows();
  const Eigen::MatrixXd b = J.gradient(e);
  const Eigen::MatrixXd c = volume ? Eigen::MatrixXd(energy_->volume_gradient(X)) : Eigen::MatrixXd::Zero(n, 3);
  ConstrainedStep step;
  Eigen::MatrixXd u, v;   // A^-1 (b + lambda0 c) and A^-1 c
  double lambda0 = 0.0;
  if (options.jacobian == JacobianMode::Exact) {
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
    if (H_.info() != Eigen::Success) throw Error("exact full-space step: J_f^T J_f could not be factored");
    Eigen::MatrixXd rhs(3 * n, volume ? 2 : 1);
    rhs.col(0) = interleave(b);
    if (volume) rhs.col(1) = interleave(c);
    const Eigen::MatrixXd sol = H_.solve(rhs);
    u = deinterleave(sol.col(0));
    if (volume) v = deinterleave(sol.col(1));
  } else {
    PcgOperator op;
    op.apply = [&](const Eigen::MatrixXd& P, Eigen::MatrixXd& AP, Eigen::MatrixXd& image) {
      AP = J.normal_product(P);
      image = P;
    };
    op.precondition = [&](const Eigen::MatrixXd& R) { return Eigen::MatrixXd(K_->solve(R)); };
    // Shifted right-hand side b + lambda0 c (see subspace_step.cpp): the inexact solves' errors then
    // vanish with the step instead of swamping it near the constrained minimum.
    lambda0 = volume ? -block_dot(c, K_->solve(b)) / block_dot(c, K_->solve(c)) : 0.0;
    Eigen::MatrixXd rhs(n, volume ? 6 : 3);
    rhs.leftCols(3) = b + lambda0 * c;
    if (volume) rhs.rightCols(3) = c;
    BatchedPcg pcg(op, rhs, n);
    auto solve_to = [&](double tolerance) {
      if (volume) pcg.run_until(combined_step_converged(rhs, c, e.constraint, tolerance), options.cg_max_iterations);
      else pcg.run(tolerance, options.cg_max_iterations);
    };
    solve_to(options.cg_tolerance);
    auto split = [&] {
      u = pcg.x().leftCols(3);
      if (volume) v = pcg.x().rightCols(3);
    };
    split();
    const double correction = volume ? volume_multiplier(u, v, c, e.constraint) : 0.0;
    const Eigen::MatrixXd du = volume ? Eigen::MatrixXd(-(u + correction * v)) : Eigen::MatrixXd(-u);
    if (du.squaredNorm() > 0.0 && !(block_dot(du, b + (lambda0 + correction) * c) < 0.0)) {
      solve_to(options.cg_tolerance * 1e-3);
      split();
    }
    step.inner_iterations = step.products = pcg.products();
  }
  const double correction = volume ? volume_multiplier(u, v, c, e.constraint) : 0.0;
  step.lambda = lambda0 + correction;
  step.du = volume ? Eigen::MatrixXd(-(u + correction * v)) : Eigen::MatrixXd(-u);
  step.slope = block_dot(step.du, b + step.lambda * c);
  if (step.du.squaredNorm() > 0.0 && !(step.slope < 0.0)) {
    // Preconditioned gradient fallback (see subspace_step.cpp).
    const Eigen::MatrixXd zb = K_->solve(b), zc = K_->solve(c);
    step.lambda = volume ? volume_multiplier(zb, zc, c, e.constraint) : 0.0;
    step.du = -(zb + step.lambda * zc);
    step.slope = block_dot(step.du, b + step.lambda * c);
    step.fallbacks = 1;
  }
  step.dx = step.du;
  if (volume) {
    step.restore_du = K_->solve(c);
    step.restore_dx = step.restore_du;
  }
  return step;
}

}  // namespace sd
