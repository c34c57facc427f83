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
  // Every block of r at once: each pair is read once per loop however many blocks there are (a step's projection
  // preconditions one block per hard constraint, and 150 pairs outgrow the cache), and the base solves them all
  // in one call. A block is contiguous (column-major, 3 columns), so it maps as a matrix of its own and its sums
  // are those of a lone block.
  const int k = size();
  const Eigen::Index rows = r.rows(), blocks = r.cols() / 3;
  const auto block = [rows](Eigen::MatrixXd& M, Eigen::Index v) {
    return Eigen::Map<Eigen::MatrixXd>(M.col(3 * v).data(), rows, 3);
  };
  Eigen::MatrixXd a(std::max(k, 1), blocks);
  Eigen::MatrixXd q = r;
  for (int i = k - 1; i >= 0; --i)
    for (Eigen::Index v = 0; v < blocks; ++v) {
      auto qv = block(q, v);
      a(i, v) = pairs_[i].rho * pairs_[i].s.cwiseProduct(qv).sum();
      qv -= a(i, v) * pairs_[i].y;
    }
  Eigen::MatrixXd z = base(q);
  for (int i = 0; i < k; ++i)
    for (Eigen::Index v = 0; v < blocks; ++v) {
      auto zv = block(z, v);
      const double b = pairs_[i].rho * pairs_[i].y.cwiseProduct(zv).sum();
      zv += (a(i, v) - b) * pairs_[i].s;
    }
  return z;
}

}  // namespace sd
