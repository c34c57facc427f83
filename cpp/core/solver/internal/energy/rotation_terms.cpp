#include "core/solver/internal/energy/rotation_terms.h"

#include <algorithm>

#include "core/solver/internal/reduced/sampled_gram.h"

namespace sd {

RotationTerms::RotationTerms(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                             const std::vector<int>& vertices)
    : U0_(U0) {
  std::vector<int> sorted = vertices, columns;
  std::sort(sorted.begin(), sorted.end());
  rows_ = energy.coordinates().restricted(sorted, columns);
  W_local_ = W.select_rows(columns).to_dense();
  X0_local_.resize(static_cast<Eigen::Index>(columns.size()), 3);
  for (size_t k = 0; k < columns.size(); ++k)
    X0_local_.row(static_cast<Eigen::Index>(k)) = energy.rest_positions().row(columns[k]);
  weights_ = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(sorted.size()));
}

Eigen::MatrixXd RotationTerms::matrix(const Eigen::MatrixXd& U) const {
  if (weights_.size() == 0) return Eigen::MatrixXd::Zero(3 * U.rows(), 3 * U.rows());
  const Vertices X = X0_local_ + W_local_ * (U - U0_);
  LaplacianRows M(&rows_.laplacian_blocks());
  M.linearize(rows_, X);
  LaplacianRows laplacian_only = M;  // the same rows with d delta_hat / dX left out
  laplacian_only.leave_out_delta_hat();
  return sampled_gram(M, W_local_, weights_) - sampled_gram(laplacian_only, W_local_, weights_);
}

}  // namespace sd
