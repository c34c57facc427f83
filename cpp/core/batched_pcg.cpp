#include "core/batched_pcg.h"

#include <cmath>

namespace sd {
namespace {

double dot3(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, Eigen::Index t) {
  return a.middleCols(3 * t, 3).cwiseProduct(b.middleCols(3 * t, 3)).sum();
}

}  // namespace

BatchedPcg::BatchedPcg(PcgOperator op, const Eigen::MatrixXd& rhs, Eigen::Index image_rows) : op_(std::move(op)) {
  const Eigen::Index s = rhs.cols() / 3;
  x_ = Eigen::MatrixXd::Zero(rhs.rows(), rhs.cols());
  image_ = Eigen::MatrixXd::Zero(image_rows, rhs.cols());
  first_image_ = Eigen::MatrixXd::Zero(image_rows, rhs.cols());
  r_ = rhs;
  z_ = op_.precondition(r_);
  p_ = z_;
  first_direction_ = z_;
  rz_.resize(s);
  for (Eigen::Index t = 0; t < s; ++t) rz_[t] = dot3(r_, z_, t);
  rz0_ = rz_;
  broken_.assign(s, false);
  first_image_valid_.assign(s, false);
}

double BatchedPcg::relative_residual(int t) const {
  if (!(rz0_[t] > 0.0)) return 0.0;  // zero right-hand side: x = 0 is exact
  return std::sqrt(std::max(rz_[t], 0.0) / rz0_[t]);
}

bool BatchedPcg::converged(double tolerance) const {
  for (int t = 0; t < systems(); ++t)
    if (!broken_[t] && relative_residual(t) > tolerance) return false;
  return true;
}

void BatchedPcg::run(double tolerance, int max_products) {
  for (int spent = 0; spent < max_products; ++spent) {
    std::vector<Eigen::Index> active;
    for (int t = 0; t < systems(); ++t)
      if (!broken_[t] && relative_residual(t) > tolerance) active.push_back(t);
    if (active.empty()) return;
    iterate(active);
  }
}

void BatchedPcg::run_until(const std::function<bool(const BatchedPcg&)>& done, int max_products) {
  for (int spent = 0; spent < max_products; ++spent) {
    if (products_ > 0 && done(*this)) return;
    std::vector<Eigen::Index> active;
    for (int t = 0; t < systems(); ++t)
      if (!broken_[t] && rz_[t] > 0.0) active.push_back(t);
    if (active.empty()) return;
    iterate(active);
  }
}

void BatchedPcg::iterate(const std::vector<Eigen::Index>& active) {
  const Eigen::Index m = x_.rows();
  {
    const Eigen::Index a = static_cast<Eigen::Index>(active.size());
    Eigen::MatrixXd P(m, 3 * a), AP, image;
    for (Eigen::Index k = 0; k < a; ++k) P.middleCols(3 * k, 3) = p_.middleCols(3 * active[k], 3);
    op_.apply(P, AP, image);
    ++products_;

    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(m, 3 * a);
    for (Eigen::Index k = 0; k < a; ++k) {
      const Eigen::Index t = active[k];
      if (!first_image_valid_[t]) {  // the first product of system t is applied to p0 = M^-1 r0
        first_image_.middleCols(3 * t, 3) = image.middleCols(3 * k, 3);
        first_image_valid_[t] = true;
      }
      const double pAp = P.middleCols(3 * k, 3).cwiseProduct(AP.middleCols(3 * k, 3)).sum();
      if (!(pAp > 0.0) || !std::isfinite(pAp)) {
        broken_[t] = true;  // A is singular along p (or numerics failed): keep the iterate reached so far
        continue;
      }
      const double alpha = rz_[t] / pAp;
      x_.middleCols(3 * t, 3) += alpha * P.middleCols(3 * k, 3);
      image_.middleCols(3 * t, 3) += alpha * image.middleCols(3 * k, 3);
      r_.middleCols(3 * t, 3) -= alpha * AP.middleCols(3 * k, 3);
      R.middleCols(3 * k, 3) = r_.middleCols(3 * t, 3);
    }
    const Eigen::MatrixXd Z = op_.precondition(R);
    for (Eigen::Index k = 0; k < a; ++k) {
      const Eigen::Index t = active[k];
      if (broken_[t]) continue;
      z_.middleCols(3 * t, 3) = Z.middleCols(3 * k, 3);
      const double rz_new = dot3(r_, z_, t);
      const double beta = rz_new / rz_[t];
      rz_[t] = rz_new;
      p_.middleCols(3 * t, 3) = z_.middleCols(3 * t, 3) + beta * p_.middleCols(3 * t, 3);
    }
  }
}

}  // namespace sd
