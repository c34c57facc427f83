#include "core/solver/internal/gauss_newton_factor.h"

#include <algorithm>

namespace sd {

bool GaussNewtonFactor::factor(const Eigen::MatrixXd& A) {
  Eigen::MatrixXd shifted = A;
  // As the exact step: single-vertex handles leave a rotation free, so A may be only semidefinite.
  shifted.diagonal().array() += 1e-12 * A.diagonal().cwiseAbs().mean();
  llt_.compute(shifted);
  ready_ = llt_.info() == Eigen::Success && llt_.matrixLLT().allFinite();
  failed_ = !ready_;
  fresh_ = ready_;
  last_products_ = 0;
  if (ready_) ++refreshes_;
  return ready_;
}

Eigen::MatrixXd GaussNewtonFactor::solve(const Eigen::MatrixXd& R) const {
  const Eigen::Index m = R.rows(), vectors = R.cols() / 3;
  Eigen::MatrixXd flat(3 * m, vectors);
  for (Eigen::Index v = 0; v < vectors; ++v)
    flat.col(v) = Eigen::Map<const Eigen::VectorXd>(R.col(3 * v).data(), 3 * m);
  llt_.solveInPlace(flat);
  Eigen::MatrixXd out(m, R.cols());
  for (Eigen::Index v = 0; v < vectors; ++v) Eigen::Map<Eigen::VectorXd>(out.col(3 * v).data(), 3 * m) = flat.col(v);
  return out;
}

void GaussNewtonFactor::record(int products) {
  last_products_ = products;
  if (fresh_ && products > threshold_) threshold_ = std::min(2 * threshold_, 1 << 20);
  fresh_ = false;
}

void GaussNewtonFactor::clear() {
  ready_ = fresh_ = failed_ = false;
  threshold_ = kRefreshProducts;
  last_products_ = 0;
}

}  // namespace sd
