#include "core/solver/internal/reduced/sampled_laplacian.h"

#include "core/solver/internal/reduced/sampled_gram.h"

namespace sd {

SampledLaplacian::SampledLaplacian(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                                   const std::vector<int>& samples, const Eigen::VectorXd& weights)
    : U0_(U0), weights_(weights) {
  sampled_ = energy.coordinates().restricted(samples, columns_);
  W_local_ = W.select_rows(columns_);
  X0_local_.resize(static_cast<Eigen::Index>(columns_.size()), 3);
  for (size_t k = 0; k < columns_.size(); ++k)
    X0_local_.row(static_cast<Eigen::Index>(k)) = energy.rest_positions().row(columns_[k]);
  M_ = LaplacianRows(&sampled_.laplacian_blocks());
}

Vertices SampledLaplacian::local_positions(const Eigen::MatrixXd& U) const {
  Eigen::MatrixXd image;
  W_local_.multiply(U - U0_, image);
  return X0_local_ + image;
}

void SampledLaplacian::evaluate(const Eigen::MatrixXd& U, EnergyEvaluation& e) const {
  e.laplacian_residual = sampled_.laplacian_residual(local_positions(U));
  e.laplacian_energy = 0.5 * (weights_.array() * e.laplacian_residual.rowwise().squaredNorm().array()).sum();
}

void SampledLaplacian::linearize(const Eigen::MatrixXd& U) {
  sampled_.jacobian_factors(local_positions(U), M_.delta_hat_jacobian());
}

Eigen::MatrixXd SampledLaplacian::gradient(const EnergyEvaluation& e) const {
  Eigen::MatrixXd out;
  W_local_.multiply_transpose(M_.multiply_transpose(weights_.asDiagonal() * e.laplacian_residual), out);
  return out;
}

Eigen::MatrixXd SampledLaplacian::product(const Eigen::MatrixXd& V) const {
  Eigen::MatrixXd image, out;
  W_local_.multiply(V, image);
  W_local_.multiply_transpose(M_.multiply_transpose(weights_.asDiagonal() * M_.multiply(image)), out);
  return out;
}

Eigen::MatrixXd SampledLaplacian::dense_matrix() const { return sampled_gram(M_, W_local_.to_dense(), weights_); }

Eigen::MatrixXd SampledLaplacian::volume_gradient(const Eigen::MatrixXd& U) const {
  // grad_i psi = 1/6 sum over the triangles (i, a, b) of x_a x x_b (docs/method.md section 5).
  const Vertices X = local_positions(U);
  Eigen::MatrixXd at_columns = Eigen::MatrixXd::Zero(X.rows(), 3);
  for (int r = 0; r < sampled_.vertex_count(); ++r) {
    const std::vector<int> ring = sampled_.one_ring(r);
    Eigen::RowVector3d g = Eigen::RowVector3d::Zero();
    for (size_t t = 0; t < ring.size(); ++t) {
      const int a = ring[(t + ring.size() - 1) % ring.size()], b = ring[t];
      g += X.row(a).cross(X.row(b));
    }
    at_columns.row(sampled_.own_column(r)) += (weights_[r] / 6.0) * g;
  }
  Eigen::MatrixXd c;
  W_local_.multiply_transpose(at_columns, c);
  return c;
}

}  // namespace sd
