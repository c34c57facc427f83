#include "core/solver/internal/steps/lbfgs_preconditioner.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sd {
namespace {

// A matrix of blocks (rows by 3 each) seen as one column per block: a block's 3 columns lie one after another.
Eigen::Map<Eigen::MatrixXd> as_columns(Eigen::MatrixXd& blocks) {
  return {blocks.data(), 3 * blocks.rows(), blocks.cols() / 3};
}
Eigen::Map<const Eigen::MatrixXd> as_columns(const Eigen::MatrixXd& blocks) {
  return {blocks.data(), 3 * blocks.rows(), blocks.cols() / 3};
}

}  // namespace

void LbfgsPreconditioner::clear() {
  count_ = 0;
  oldest_ = 0;
}

void LbfgsPreconditioner::add_pair(const Eigen::MatrixXd& s, const Eigen::MatrixXd& y) {
  if (capacity_ <= 0) return;
  const Eigen::Map<const Eigen::VectorXd> sv(s.data(), s.size()), yv(y.data(), y.size());
  const double sy = sv.dot(yv);
  if (!(sy > 0.0) || !std::isfinite(sy)) return;
  if (S_.rows() != s.size() || S_.cols() != capacity_) {  // the first pair, or blocks of another size
    S_.resize(s.size(), capacity_);
    Y_.resize(s.size(), capacity_);
    U_.resize(capacity_, capacity_);
    clear();
  }
  // A new pair takes the slot after the newest pair's: the oldest's when full, whose row and column of U_ then go.
  const int slot = (oldest_ + count_) % capacity_;
  if (count_ == capacity_) {
    oldest_ = (oldest_ + 1) % capacity_;
    U_.topLeftCorner(count_ - 1, count_ - 1) = U_.bottomRightCorner(count_ - 1, count_ - 1).eval();
  } else {
    ++count_;
  }
  S_.col(slot) = sv;
  Y_.col(slot) = yv;
  const Eigen::VectorXd s_dot_y = S_.leftCols(count_).transpose() * yv;  // by slot
  for (int i = 0; i < count_; ++i) U_(i, count_ - 1) = s_dot_y[slot_of(i)];
  U_(count_ - 1, count_ - 1) = sy;  // the curvature just checked, not the product's rounding of it
}

void LbfgsPreconditioner::resize(int capacity) {
  capacity = std::max(capacity, 0);
  if (capacity == capacity_) return;
  // Rare (the option changed): the newest pairs that fit are added again, oldest first.
  std::vector<std::pair<Eigen::MatrixXd, Eigen::MatrixXd>> kept;
  const Eigen::Index rows = S_.rows() / 3;
  for (int i = std::max(0, count_ - capacity); i < count_; ++i) {
    const int slot = slot_of(i);
    kept.emplace_back(Eigen::Map<const Eigen::MatrixXd>(S_.col(slot).data(), rows, 3),
                      Eigen::Map<const Eigen::MatrixXd>(Y_.col(slot).data(), rows, 3));
  }
  capacity_ = capacity;
  S_.resize(0, 0);
  clear();
  for (const auto& [s, y] : kept) add_pair(s, y);
}

Eigen::MatrixXd LbfgsPreconditioner::by_age(const Eigen::MatrixXd& by_slot) const {
  Eigen::MatrixXd out(count_, by_slot.cols());
  for (int i = 0; i < count_; ++i) out.row(i) = by_slot.row(slot_of(i));
  return out;
}

Eigen::MatrixXd LbfgsPreconditioner::by_slot(const Eigen::MatrixXd& by_age) const {
  Eigen::MatrixXd out(count_, by_age.cols());
  for (int i = 0; i < count_; ++i) out.row(slot_of(i)) = by_age.row(i);
  return out;
}

Eigen::MatrixXd LbfgsPreconditioner::apply(const Eigen::MatrixXd& r,
                                           const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& base) const {
  eigen_assert(r.cols() % 3 == 0 && (count_ == 0 || 3 * r.rows() == S_.rows()));
  if (count_ == 0) return base(r);
  // The two-loop recursion (Nocedal and Wright, algorithm 7.4) in matrix form (Byrd, Nocedal and Schnabel 1994).
  // With U the upper triangle of s_i . y_j (pairs oldest first; its diagonal 1 / rho_i), the first loop's
  // coefficients a_i = rho_i s_i . (r - sum_{j newer} a_j y_j) solve U a = S^T r, and the second loop's updates
  // c_i = a_i - rho_i y_i . (z0 + sum_{j older} c_j s_j) solve U^T c = diag(U) a - Y^T z0, with z0 = base(r - Y a)
  // and H r = z0 + S c. Every block of r is a column of these products: the pairs are read in four matrix
  // products however many blocks there are (one per hard constraint in a step's projection), and the base
  // solves every block in one call.
  const auto S = S_.leftCols(count_), Y = Y_.leftCols(count_);
  const auto U = U_.topLeftCorner(count_, count_).triangularView<Eigen::Upper>();
  Eigen::MatrixXd a = by_age(S.transpose() * as_columns(r));
  U.solveInPlace(a);
  Eigen::MatrixXd q = r;
  as_columns(q).noalias() -= Y * by_slot(a);
  Eigen::MatrixXd z = base(q);
  Eigen::MatrixXd c = U_.diagonal().head(count_).asDiagonal() * a - by_age(Y.transpose() * as_columns(z));
  U.transpose().solveInPlace(c);
  as_columns(z).noalias() += S * by_slot(c);
  return z;
}

}  // namespace sd
