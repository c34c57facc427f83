#include "core/solver/internal/steps/lbfgs_preconditioner.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sd {
namespace {

double dot(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return a.cwiseProduct(b).sum(); }

}  // namespace

void LbfgsPreconditioner::add_pair(const Eigen::MatrixXd& s, const Eigen::MatrixXd& y) {
  if (capacity_ <= 0) return;
  const double sy = dot(s, y);
  if (!(sy > 0.0) || !std::isfinite(sy)) return;
  pairs_.push_back({s, y, 1.0 / sy});
  while (static_cast<int>(pairs_.size()) > capacity_) pairs_.pop_front();
}

void LbfgsPreconditioner::resize(int capacity) {
  capacity_ = capacity;
  while (static_cast<int>(pairs_.size()) > std::max(capacity_, 0)) pairs_.pop_front();
}

Eigen::MatrixXd LbfgsPreconditioner::apply(const Eigen::MatrixXd& r,
                                           const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& base) const {
  const int k = size();
  std::vector<double> a(k);
  Eigen::MatrixXd q = r;
  for (int i = k - 1; i >= 0; --i) {
    a[i] = pairs_[i].rho * dot(pairs_[i].s, q);
    q -= a[i] * pairs_[i].y;
  }
  Eigen::MatrixXd z = base(q);
  for (int i = 0; i < k; ++i) {
    const double b = pairs_[i].rho * dot(pairs_[i].y, z);
    z += (a[i] - b) * pairs_[i].s;
  }
  return z;
}

}  // namespace sd
