#include "core/solver/internal/steps/gauss_newton_factor.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sd {

bool GaussNewtonFactor::factor(const Eigen::MatrixXd& P) {
  Eigen::MatrixXd shifted = P;
  // As the exact step: single-vertex handles leave a rotation free, so P may be only semidefinite.
  shifted.diagonal().array() += 1e-12 * P.diagonal().cwiseAbs().mean();
  const Eigen::LLT<Eigen::MatrixXd> llt(shifted);
  ready_ = llt.info() == Eigen::Success && llt.matrixLLT().allFinite();
  factor_ = ready_ ? PackedFactor(llt.matrixLLT()) : PackedFactor();
  ready_ = ready_ && factor_.valid();
  failed_ = !ready_;
  runs_ = 0;
  debt_ = 0;
  full_runs_ = 0;
  full_excess_ = 0;
  return ready_;
}

Eigen::MatrixXd solve_stacked(const Eigen::LLT<Eigen::MatrixXd>& llt, const Eigen::MatrixXd& R) {
  const Eigen::Index m = R.rows(), vectors = R.cols() / 3;
  Eigen::MatrixXd flat(3 * m, vectors);
  for (Eigen::Index v = 0; v < vectors; ++v)
    flat.col(v) = Eigen::Map<const Eigen::VectorXd>(R.col(3 * v).data(), 3 * m);
  llt.solveInPlace(flat);
  Eigen::MatrixXd out(m, R.cols());
  for (Eigen::Index v = 0; v < vectors; ++v) Eigen::Map<Eigen::VectorXd>(out.col(3 * v).data(), 3 * m) = flat.col(v);
  return out;
}

Eigen::MatrixXd GaussNewtonFactor::solve(const Eigen::MatrixXd& R) const {
  // Each m x 3 block of R is one vector of the 3m unknowns (index axis * m + j): its columns one after another.
  Eigen::MatrixXd out = R;
  for (Eigen::Index v = 0; v < R.cols() / 3; ++v) factor_.solve_in_place(out.col(3 * v).data());
  return out;
}

double GaussNewtonFactor::price(double cost) const {
  // The first factor after a run of long PCG solves is bought at half its cost (gauss_newton_factor.h).
  const bool long_runs = !ready_ && full_runs_ > 0 && full_excess_ >= kLongRunExcess * full_runs_;
  return long_runs ? 0.5 * cost : cost;
}

int GaussNewtonFactor::products_before(double price) const {
  const double remaining = std::ceil(price - debt_);
  if (failed_ || !(remaining < 1e6)) return std::numeric_limits<int>::max();
  return kGoodProducts + static_cast<int>(std::max(1.0, remaining));
}

bool GaussNewtonFactor::due(double cost) {
  if (failed_ || debt_ < price(cost)) return false;
  if (ready_ && runs_ <= kServingRuns) {  // it did not pay for itself
    ready_ = false;
    failed_ = true;
    return false;
  }
  return true;
}

void GaussNewtonFactor::record(int products, double weight, bool full_integration) {
  ++runs_;
  debt_ += weight * std::max(0, products - kGoodProducts);
  if (full_integration) {
    ++full_runs_;
    full_excess_ += std::max(0, products - kGoodProducts);
  }
}

void GaussNewtonFactor::clear() {
  ready_ = failed_ = false;
  runs_ = full_runs_ = 0;
  debt_ = full_excess_ = 0;
}

}  // namespace sd
