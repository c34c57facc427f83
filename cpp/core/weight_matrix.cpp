#include "core/weight_matrix.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"

namespace sd {
namespace {

// The two products are the solver's inner loop (design.md section 4). Accumulation is in double whatever
// the storage type, and both vectorise without -ffast-math (no reduction the compiler must reorder):
//   multiply:           a register block of 4 rows x up to 6 columns over P copied interleaved
//                       (Pt[j * k + c], m k doubles): each loaded P value serves 4 rows, so the kernel
//                       is no longer bound by loads (it was: 4 columns per sweep, time linear in k, and
//                       6 columns read W twice). W is read once for k <= 6 (the solver's x, y, z for two
//                       right-hand sides), once per 6 columns above;
//   multiply_transpose: 4 rows of W at a time added into each column of the output (an axpy, no
//                       reduction); the 4 rows stay in L1 across the k columns, so W is read once.
// Measured (n = 49614, m = 300, float64, native -O3): k = 6 forward 25.8 -> 11.9 ms, k = 3 12.4 -> 7.7 ms.

// 4 rows x K columns register block over P interleaved (Pt[j * K + c]): each P value loaded once per 4 rows.
template <int K, typename T>
void multiply_block_k(const T* W, int n, int m, const double* Pt, double* const* out) {
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    const T* w0 = W + static_cast<std::size_t>(i) * m;
    const T* w1 = w0 + m; const T* w2 = w1 + m; const T* w3 = w2 + m;
    double a0[K] = {}, a1[K] = {}, a2[K] = {}, a3[K] = {};
    for (int j = 0; j < m; ++j) {
      const double* p = Pt + static_cast<std::size_t>(j) * K;
      const double v0 = w0[j], v1 = w1[j], v2 = w2[j], v3 = w3[j];
      for (int c = 0; c < K; ++c) { a0[c] += v0 * p[c]; a1[c] += v1 * p[c]; a2[c] += v2 * p[c]; a3[c] += v3 * p[c]; }
    }
    for (int c = 0; c < K; ++c) { out[c][i] = a0[c]; out[c][i + 1] = a1[c]; out[c][i + 2] = a2[c]; out[c][i + 3] = a3[c]; }
  }
  for (; i < n; ++i) {
    const T* w = W + static_cast<std::size_t>(i) * m;
    double a[K] = {};
    for (int j = 0; j < m; ++j) for (int c = 0; c < K; ++c) a[c] += static_cast<double>(w[j]) * Pt[static_cast<std::size_t>(j) * K + c];
    for (int c = 0; c < K; ++c) out[c][i] = a[c];
  }
}

template <typename T>
void multiply_impl(const T* W, int n, int m, const Eigen::MatrixXd& P, Eigen::MatrixXd& out) {
  const int k = static_cast<int>(P.cols());
  for (int c0 = 0; c0 < k; c0 += 6) {
    const int kc = std::min(6, k - c0);
    std::vector<double> Pt(static_cast<std::size_t>(m) * kc);
    for (int j = 0; j < m; ++j) for (int c = 0; c < kc; ++c) Pt[static_cast<std::size_t>(j) * kc + c] = P(j, c0 + c);
    double* o[6];
    for (int c = 0; c < kc; ++c) o[c] = out.col(c0 + c).data();
    switch (kc) {
      case 1: multiply_block_k<1>(W, n, m, Pt.data(), o); break;
      case 2: multiply_block_k<2>(W, n, m, Pt.data(), o); break;
      case 3: multiply_block_k<3>(W, n, m, Pt.data(), o); break;
      case 4: multiply_block_k<4>(W, n, m, Pt.data(), o); break;
      case 5: multiply_block_k<5>(W, n, m, Pt.data(), o); break;
      default: multiply_block_k<6>(W, n, m, Pt.data(), o); break;
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
