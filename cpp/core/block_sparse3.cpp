#include "core/block_sparse3.h"

#include <string>

#include "core/error.h"

namespace sd {
namespace {

void check_rows(const BlockPattern& p, const Eigen::MatrixXd& x, const char* what) {
  if (x.rows() != p.vertex_count() || x.cols() % 3 != 0)
    throw Error(std::string(what) + ": a block of " + std::to_string(x.rows()) + " x " + std::to_string(x.cols()) +
                " for " + std::to_string(p.vertex_count()) + " vertices (expected #V by a multiple of 3)");
}

}  // namespace

BlockSparse3::BlockSparse3(std::shared_ptr<const BlockPattern> pattern)
    : pattern_(std::move(pattern)), values_(9 * static_cast<std::size_t>(pattern_->block_count()), 0.0) {}

Eigen::MatrixXd BlockSparse3::multiply(const Eigen::MatrixXd& x) const {
  const BlockPattern& p = *pattern_;
  check_rows(p, x, "block matrix product");
  const int n = p.vertex_count();
  Eigen::MatrixXd out(n, x.cols());
  for (Eigen::Index t = 0; t < x.cols(); t += 3) {
    const double *x0 = x.col(t).data(), *x1 = x.col(t + 1).data(), *x2 = x.col(t + 2).data();
    double *o0 = out.col(t).data(), *o1 = out.col(t + 1).data(), *o2 = out.col(t + 2).data();
    for (int i = 0; i < n; ++i) {
      double a0 = 0, a1 = 0, a2 = 0;
      for (int k = p.row_start[i]; k < p.row_start[i + 1]; ++k) {
        const double* b = block(k);
        const int j = p.column[k];
        const double v0 = x0[j], v1 = x1[j], v2 = x2[j];
        a0 += b[0] * v0 + b[1] * v1 + b[2] * v2;
        a1 += b[3] * v0 + b[4] * v1 + b[5] * v2;
        a2 += b[6] * v0 + b[7] * v1 + b[8] * v2;
      }
      o0[i] = a0;
      o1[i] = a1;
      o2[i] = a2;
    }
  }
  return out;
}

Eigen::MatrixXd BlockSparse3::multiply_transpose(const Eigen::MatrixXd& x) const {
  const BlockPattern& p = *pattern_;
  check_rows(p, x, "block matrix transposed product");
  const int n = p.vertex_count();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, x.cols());
  for (Eigen::Index t = 0; t < x.cols(); t += 3) {
    const double *x0 = x.col(t).data(), *x1 = x.col(t + 1).data(), *x2 = x.col(t + 2).data();
    double *o0 = out.col(t).data(), *o1 = out.col(t + 1).data(), *o2 = out.col(t + 2).data();
    for (int i = 0; i < n; ++i) {
      const double v0 = x0[i], v1 = x1[i], v2 = x2[i];
      for (int k = p.row_start[i]; k < p.row_start[i + 1]; ++k) {
        const double* b = block(k);
        const int j = p.column[k];
        o0[j] += b[0] * v0 + b[3] * v1 + b[6] * v2;
        o1[j] += b[1] * v0 + b[4] * v1 + b[7] * v2;
        o2[j] += b[2] * v0 + b[5] * v1 + b[8] * v2;
      }
    }
  }
  return out;
}

Eigen::SparseMatrix<double> BlockSparse3::to_sparse() const {
  const BlockPattern& p = *pattern_;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(9 * static_cast<std::size_t>(p.block_count()));
  for (int i = 0; i < p.vertex_count(); ++i)
    for (int k = p.row_start[i]; k < p.row_start[i + 1]; ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) entries.emplace_back(3 * i + r, 3 * p.column[k] + c, block(k)[3 * r + c]);
  const int size = 3 * p.vertex_count();
  Eigen::SparseMatrix<double> out(size, size);
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

}  // namespace sd
