#include "core/solver/internal/reduced_subspace.h"

#include <Eigen/Cholesky>
#include <string>

#include "core/error.h"
#include "core/solver/internal/pcg_step.h"

namespace sd {
namespace {

Eigen::VectorXd flat(const Eigen::MatrixXd& block) { return Eigen::Map<const Eigen::VectorXd>(block.data(), block.size()); }
Eigen::MatrixXd unflat(const Eigen::VectorXd& v, Eigen::Index m) { return Eigen::Map<const Eigen::MatrixXd>(v.data(), m, 3); }

// H V for each m by 3 block of V: the handle Gram matrix acts on x, y and z alike.
Eigen::MatrixXd per_axis(const Eigen::MatrixXd& H, const Eigen::MatrixXd& V) { return H * V; }

}  // namespace

ReducedSubspace::ReducedSubspace(const DeformationEnergy& energy, const WeightMatrix& W, const Eigen::MatrixXd& U0,
                                 SubspaceStep& subspace, const Cubature& cubature)
    : energy_(&energy), W_(&W), U0_(U0), subspace_(&subspace), weights_(cubature.weights) {
  sampled_ = energy.coordinates().restricted(cubature.samples, columns_);
  W_local_ = W.select_rows(columns_);
  X0_local_.resize(static_cast<Eigen::Index>(columns_.size()), 3);
  for (size_t k = 0; k < columns_.size(); ++k) X0_local_.row(static_cast<Eigen::Index>(k)) = energy.rest_positions().row(columns_[k]);
  M_ = LaplacianRows(&sampled_.laplacian_blocks());
}

Vertices ReducedSubspace::local_positions(const Eigen::MatrixXd& U) const {
  Eigen::MatrixXd image;
  W_local_.multiply(U - U0_, image);
  return X0_local_ + image;
}

EnergyEvaluation ReducedSubspace::evaluate(const Vertices& X, const Eigen::MatrixXd& U) const {
  EnergyEvaluation e;
  e.laplacian_residual = sampled_.laplacian_residual(local_positions(U));
  e.laplacian_energy = 0.5 * (weights_.array() * e.laplacian_residual.rowwise().squaredNorm().array()).sum();
  e.constraint = energy_->constraints(X, &e.volume);
  energy_->update_position_terms(X, e);
  return e;
}

void ReducedSubspace::linearize(const Eigen::MatrixXd& U) {
  sampled_.jacobian_factors(local_positions(U), M_.delta_hat_jacobian());
}

Eigen::MatrixXd ReducedSubspace::handle_gradient(const EnergyEvaluation& e, const Vertices& X) const {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(X.rows(), 3);
  const Eigen::VectorXd& w = energy_->handle_row_weights();
  const auto& handles = energy_->handle_vertices();
  for (size_t k = 0; k < handles.size(); ++k)
    out.row(handles[k]) += w[static_cast<Eigen::Index>(k)] * e.position_residual.row(static_cast<Eigen::Index>(k));
  return out;
}

Eigen::MatrixXd ReducedSubspace::sampled_gradient(const EnergyEvaluation& e) const {
  Eigen::MatrixXd out;
  W_local_.multiply_transpose(M_.multiply_transpose(weights_.asDiagonal() * e.laplacian_residual), out);
  return out;
}

Eigen::MatrixXd ReducedSubspace::gradient(const EnergyEvaluation& e, const Vertices& X) const {
  Eigen::MatrixXd out;
  W_->multiply_transpose(handle_gradient(e, X), out);
  return out + sampled_gradient(e);
}

Eigen::MatrixXd ReducedSubspace::product(const Eigen::MatrixXd& V) const {
  Eigen::MatrixXd image, out;
  W_local_.multiply(V, image);
  W_local_.multiply_transpose(M_.multiply_transpose(weights_.asDiagonal() * M_.multiply(image)), out);
  out += per_axis(subspace_->handle_gram(), V);
  if (subspace_->regularization().active()) out += subspace_->regularization().hessian_times(V);
  return out;
}

Eigen::MatrixXd ReducedSubspace::dense_matrix() const {
  const Eigen::Index m = W_->cols(), samples = weights_.size();
  // J = M_S W_S (x) I3 as 3 samples by 3m: column a m + j is M_S applied to W_S's column j on axis a.
  const Eigen::MatrixXd Wl = W_local_.to_dense();
  Eigen::MatrixXd J(3 * samples, 3 * m);
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(Wl.rows(), 3 * m);
    for (Eigen::Index j = 0; j < m; ++j) unit.col(3 * j + axis) = Wl.col(j);
    const Eigen::MatrixXd image = M_.multiply(unit);  // samples by 3m: column 3j + r is component r
    for (Eigen::Index s = 0; s < samples; ++s)
      for (Eigen::Index j = 0; j < m; ++j)
        for (int r = 0; r < 3; ++r) J(3 * s + r, axis * m + j) = image(s, 3 * j + r);
  }
  for (Eigen::Index s = 0; s < samples; ++s) J.middleRows(3 * s, 3) *= std::sqrt(weights_[s]);
  Eigen::MatrixXd A = J.transpose() * J;
  for (int axis = 0; axis < 3; ++axis) {
    A.block(axis * m, axis * m, m, m) += subspace_->handle_gram();
    if (subspace_->regularization().active())
      A.block(axis * m, axis * m, m, m) += subspace_->regularization().eps() * subspace_->regularization().penalty();
  }
  return A;
}

ConstrainedStep ReducedSubspace::exact_step(const Eigen::MatrixXd& b, const Eigen::MatrixXd& c,
                                            const Eigen::VectorXd& g, bool volume) const {
  const Eigen::Index m = W_->cols(), K = c.cols() / 3;
  Eigen::MatrixXd A = dense_matrix();
  A.diagonal().array() += 1e-12 * A.diagonal().cwiseAbs().mean();  // as the subspace's exact step
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive())
    throw Error(ErrorCode::NumericalFailure, "exact reduced step: the sampled normal matrix could not be factored");
  Eigen::MatrixXd rhs(3 * m, volume ? 1 + K : 1);
  rhs.col(0) = flat(b);
  for (Eigen::Index k = 0; volume && k < K; ++k) rhs.col(1 + k) = flat(c.middleCols(3 * k, 3));
  const Eigen::MatrixXd sol = ldlt.solve(rhs);
  const Eigen::MatrixXd u = unflat(sol.col(0), m);
  Eigen::MatrixXd V(m, volume ? 3 * K : 0);
  for (Eigen::Index k = 0; volume && k < K; ++k) V.middleCols(3 * k, 3) = unflat(sol.col(1 + k), m);
  ConstrainedStep step;
  step.lambda = volume ? volume_multipliers(u, V, c, g) : Eigen::VectorXd(Eigen::VectorXd::Zero(K));
  step.du = volume ? Eigen::MatrixXd(-add_blocks(u, V, step.lambda)) : Eigen::MatrixXd(-u);
  step.slope = block_dot(step.du, add_blocks(b, c, step.lambda));
  return step;
}

ConstrainedStep ReducedSubspace::step(const EnergyEvaluation& e, const Vertices& X, const Eigen::MatrixXd& U,
                                      const SolverOptions& options) {
  if (!subspace_->factored()) throw Error("subspace: no handles are set, so the step is undefined");
  subspace_->sync_options(options);
  linearize(U);
  const int K = energy_->constraint_count();
  const bool volume = options.volume;
  // One transposed pass over W serves the handle term's gradient and the constraints' (the sampled term needs
  // W_S alone).
  Eigen::MatrixXd G(X.rows(), volume ? 3 + 3 * K : 3), bc;
  G.leftCols(3) = handle_gradient(e, X);
  if (volume) G.rightCols(3 * K) = energy_->constraint_gradients(X);
  W_->multiply_transpose(G, bc);
  Eigen::MatrixXd b = bc.leftCols(3) + sampled_gradient(e);
  if (subspace_->regularization().active()) b += subspace_->regularization().gradient(U);
  const Eigen::MatrixXd c = volume ? Eigen::MatrixXd(bc.rightCols(3 * K)) : Eigen::MatrixXd::Zero(W_->cols(), 3 * K);
  ConstrainedStep step;
  if (options.jacobian == JacobianMode::Exact) {
    step = exact_step(b, c, e.constraint, volume);
  } else {
    PcgStepProblem problem;
    problem.product = [&](const Eigen::MatrixXd& V, Eigen::MatrixXd& image) {
      image.resize(0, V.cols());
      return product(V);
    };
    problem.base_preconditioner = [this](const Eigen::MatrixXd& R) { return subspace_->precondition(R); };
    std::unique_ptr<ProjectedPcg> pcg;
    step = pcg_step(problem, memory_, b, c, e.constraint, energy_->rest_volume(), volume, options, pcg);
  }
  // One forward pass maps the step and the restoring directions N^-1 c_k.
  Eigen::MatrixXd D(W_->cols(), volume ? 3 + 3 * K : 3), image;
  D.leftCols(3) = step.du;
  if (volume) D.rightCols(3 * K) = subspace_->precondition(c);
  W_->multiply(D, image);
  step.dx = image.leftCols(3);
  if (volume) {
    step.restore_du = D.rightCols(3 * K);
    step.restore_dx = image.rightCols(3 * K);
  }
  // Passes over the whole of W: the handle gradient, the volume gradients, the forward map.
  step.passes = WeightMatrix::passes(static_cast<int>(G.cols())) + WeightMatrix::passes(static_cast<int>(D.cols()));
  return step;
}

}  // namespace sd
