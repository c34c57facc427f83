#include "core/solver/internal/reduced/sampled_gram.h"

#include <cmath>

#include "core/solver/internal/steps/row_gram.h"

namespace sd {

Eigen::MatrixXd sampled_gram(const LaplacianRows& M, const Eigen::MatrixXd& W_local, const Eigen::VectorXd& weights) {
  const Eigen::Index m = W_local.cols(), rows = weights.size();
  // J = M W_S (x) I3 as 3 rows by 3m: column a m + j is M applied to W_S's column j on axis a.
  Eigen::MatrixXd J(3 * rows, 3 * m);
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(W_local.rows(), 3 * m);
    for (Eigen::Index j = 0; j < m; ++j) unit.col(3 * j + axis) = W_local.col(j);
    const Eigen::MatrixXd image = M.multiply(unit);  // rows by 3m: column 3j + r is component r
    for (Eigen::Index s = 0; s < rows; ++s)
      for (Eigen::Index j = 0; j < m; ++j)
        for (int r = 0; r < 3; ++r) J(3 * s + r, axis * m + j) = image(s, 3 * j + r);
  }
  for (Eigen::Index s = 0; s < rows; ++s) J.middleRows(3 * s, 3) *= std::sqrt(weights[s]);
  return row_gram(
      static_cast<int>(J.rows()), static_cast<int>(J.cols()),
      [&](int lo, int hi) { return Eigen::MatrixXd(J.middleRows(lo, hi - lo)); }, 512);
}

}  // namespace sd
