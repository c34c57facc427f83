#include "core/arap/internal/anderson_acceleration.h"

#include <Eigen/QR>

namespace sd {

void AndersonAcceleration::set_depth(int depth) {
  if (depth != depth_) reset();
  depth_ = depth;
}

void AndersonAcceleration::reset() {
  has_last_ = false;
  dF_.clear();
  dG_.clear();
}

Eigen::VectorXd AndersonAcceleration::next(const Eigen::VectorXd& x, const Eigen::VectorXd& g) {
  if (depth_ <= 0) return g;
  const Eigen::VectorXd f = g - x;
  if (has_last_ && last_f_.size() == f.size()) {
    dF_.push_back(f - last_f_);
    dG_.push_back(g - last_g_);
    while (static_cast<int>(dF_.size()) > depth_) {
      dF_.pop_front();
      dG_.pop_front();
    }
  } else {
    dF_.clear();
    dG_.clear();
  }
  last_f_ = f;
  last_g_ = g;
  has_last_ = true;
  if (dF_.empty()) return g;

  const Eigen::Index k = static_cast<Eigen::Index>(dF_.size());
  Eigen::MatrixXd F(f.size(), k);
  for (Eigen::Index j = 0; j < k; ++j) F.col(j) = dF_[j];
  // Rank-revealing QR: consecutive differences become nearly parallel as the iteration converges.
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(F);
  const Eigen::VectorXd theta = qr.solve(f);
  if (!theta.allFinite()) return g;
  Eigen::VectorXd out = g;
  for (Eigen::Index j = 0; j < k; ++j) out -= theta[j] * dG_[j];
  return out;
}

}  // namespace sd
