#include "core/solver/internal/steps/packed_factor.h"

#include <cmath>

#include "core/solver/internal/two_lane_kernels.h"

namespace sd {

PackedFactor::PackedFactor(const Eigen::MatrixXd& L) : n_(L.rows()), valid_(true) {
  rows_.resize(static_cast<size_t>(n_ * (n_ + 1) / 2));
  inverse_diagonal_.resize(static_cast<size_t>(n_));
  for (Eigen::Index i = 0; i < n_; ++i) {
    float* r = rows_.data() + i * (i + 1) / 2;
    for (Eigen::Index j = 0; j <= i; ++j) {
      r[j] = static_cast<float>(L(i, j));
      valid_ = valid_ && std::isfinite(r[j]);
    }
    valid_ = valid_ && std::isnormal(r[i]) && r[i] > 0.0f;  // a subnormal diagonal has lost its digits
    inverse_diagonal_[static_cast<size_t>(i)] = 1.0 / static_cast<double>(r[i]);
  }
}

void PackedFactor::solve_in_place(double* x) const {
  // L~ y = x: row i's entries before the diagonal dotted with y's first i entries.
  for (Eigen::Index i = 0; i < n_; ++i)
    x[i] = (x[i] - two_lane::dot(row(i), x, i)) * inverse_diagonal_[static_cast<size_t>(i)];
  // L~^T z = y, by columns of L~^T (rows of L~): z_j is final once the later rows are taken off.
  for (Eigen::Index j = n_ - 1; j >= 0; --j) {
    x[j] *= inverse_diagonal_[static_cast<size_t>(j)];
    two_lane::subtract_scaled(row(j), x[j], x, j);
  }
}

}  // namespace sd
