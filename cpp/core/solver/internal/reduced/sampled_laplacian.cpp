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

void SampledLaplacian::linearize(const Eigen::MatrixXd& U) { M_.linearize(sampled_, local_positions(U)); }

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

}  // namespace sd
