#include "core/weight_matrix.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <string>

#include "core/error.h"

namespace sd {
namespace {

// The two products are the solver's inner loop (design.md section 4). Both are written so that W is read
// from memory exactly once per call and the compiler can vectorise without -ffast-math:
//   multiply:           up to 4 columns of P per sweep over a row, each with 4 independent partial sums
//                       (no floating-point reduction the compiler would have to reorder);
//   multiply_transpose: 4 rows of W at a time added into a column of the output (an axpy, no reduction),
//                       so each output element is loaded and stored once per 4 rows.
// Accumulation is in double whatever the storage type.

template <int K, typename T>
void multiply_rows_k(const T* W, int n, int m, const double* const* p, double* const* out) {
  for (int i = 0; i < n; ++i) {
    const T* w = W + static_cast<std::size_t>(i) * m;
    double acc[K][4] = {};
    int j = 0;
    for (; j + 4 <= m; j += 4)
      for (int c = 0; c < K; ++c)
        for (int l = 0; l < 4; ++l) acc[c][l] += static_cast<double>(w[j + l]) * p[c][j + l];
    for (int c = 0; c < K; ++c) {
      double s = (acc[c][0] + acc[c][1]) + (acc[c][2] + acc[c][3]);
      for (int jj = j; jj < m; ++jj) s += static_cast<double>(w[jj]) * p[c][jj];
      out[c][i] = s;
    }
  }
}

template <typename T>
void multiply_impl(const T* W, int n, int m, const Eigen::MatrixXd& P, Eigen::MatrixXd& out) {
  const int k = static_cast<int>(P.cols());
  // Columns in chunks of 4: one chunk reads W once; k <= 4 (x, y, z, volume gradient) is one chunk.
  for (int c0 = 0; c0 < k; c0 += 4) {
    const int kc = std::min(4, k - c0);
    const double* p[4];
    double* o[4];
    for (int c = 0; c < kc; ++c) {
      p[c] = P.col(c0 + c).data();
      o[c] = out.col(c0 + c).data();
    }
    switch (kc) {
      case 1: multiply_rows_k<1>(W, n, m, p, o); break;
      case 2: multiply_rows_k<2>(W, n, m, p, o); break;
      case 3: multiply_rows_k<3>(W, n, m, p, o); break;
      default: multiply_rows_k<4>(W, n, m, p, o); break;
    }
  }
}

template <typename T>
void multiply_transpose_impl(const T* W, int n, int m, const Eigen::MatrixXd& R, Eigen::MatrixXd& out) {
  const int k = static_cast<int>(R.cols());
  out.setZero(m, k);
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    const T* w0 = W + static_cast<std::size_t>(i) * m;
    const T* w1 = w0 + m;
    const T* w2 = w1 + m;
    const T* w3 = w2 + m;
    for (int c = 0; c < k; ++c) {
      const double r0 = R(i, c), r1 = R(i + 1, c), r2 = R(i + 2, c), r3 = R(i + 3, c);
      double* o = out.col(c).data();
      for (int j = 0; j < m; ++j)
        o[j] += (r0 * static_cast<double>(w0[j]) + r1 * static_cast<double>(w1[j])) +
                (r2 * static_cast<double>(w2[j]) + r3 * static_cast<double>(w3[j]));
    }
  }
  for (; i < n; ++i) {
    const T* w = W + static_cast<std::size_t>(i) * m;
    for (int c = 0; c < k; ++c) {
      const double r = R(i, c);
      double* o = out.col(c).data();
      for (int j = 0; j < m; ++j) o[j] += r * static_cast<double>(w[j]);
    }
  }
}

}  // namespace

WeightMatrix::WeightMatrix(int rows, int cols, bool single_precision)
    : rows_(rows), cols_(cols), single_(single_precision) {
  if (rows < 0 || cols < 0) throw Error("weight matrix: negative size");
  const std::size_t count = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  if (single_)
    values32_.assign(count, 0.0f);
  else
    values64_.assign(count, 0.0);
}

std::size_t WeightMatrix::bytes() const {
  return single_ ? values32_.size() * sizeof(float) : values64_.size() * sizeof(double);
}

double WeightMatrix::get(int i, int j) const {
  assert(i >= 0 && i < rows_ && j >= 0 && j < cols_);
  const std::size_t at = static_cast<std::size_t>(i) * cols_ + j;
  return single_ ? static_cast<double>(values32_[at]) : values64_[at];
}

void WeightMatrix::set(int i, int j, double value) {
  assert(i >= 0 && i < rows_ && j >= 0 && j < cols_);
  const std::size_t at = static_cast<std::size_t>(i) * cols_ + j;
  if (single_)
    values32_[at] = static_cast<float>(value);
  else
    values64_[at] = value;
}

void WeightMatrix::set_row(int i, const Eigen::RowVectorXd& row) {
  assert(i >= 0 && i < rows_ && row.size() == cols_);
  const std::size_t at = static_cast<std::size_t>(i) * cols_;
  if (single_)
    for (int j = 0; j < cols_; ++j) values32_[at + j] = static_cast<float>(row[j]);
  else
    std::copy(row.data(), row.data() + cols_, values64_.begin() + static_cast<std::ptrdiff_t>(at));
}

void WeightMatrix::multiply(const Eigen::MatrixXd& P, Eigen::MatrixXd& out) const {
  if (P.rows() != cols_)
    throw Error("W * P: P has " + std::to_string(P.rows()) + " rows, W has " + std::to_string(cols_) + " columns");
  out.resize(rows_, P.cols());
  if (single_)
    multiply_impl(values32_.data(), rows_, cols_, P, out);
  else
    multiply_impl(values64_.data(), rows_, cols_, P, out);
}

void WeightMatrix::multiply_transpose(const Eigen::MatrixXd& R, Eigen::MatrixXd& out) const {
  if (R.rows() != rows_)
    throw Error("W^T * R: R has " + std::to_string(R.rows()) + " rows, W has " + std::to_string(rows_) + " rows");
  if (single_)
    multiply_transpose_impl(values32_.data(), rows_, cols_, R, out);
  else
    multiply_transpose_impl(values64_.data(), rows_, cols_, R, out);
}

Eigen::MatrixXd WeightMatrix::to_dense() const {
  Eigen::MatrixXd dense(rows_, cols_);
  for (int i = 0; i < rows_; ++i)
    for (int j = 0; j < cols_; ++j) dense(i, j) = get(i, j);
  return dense;
}

const void* WeightMatrix::data() const {
  return single_ ? static_cast<const void*>(values32_.data()) : static_cast<const void*>(values64_.data());
}

}  // namespace sd
