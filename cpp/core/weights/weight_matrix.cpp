#include "core/weights/weight_matrix.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"

namespace sd {
namespace {

// The two products are the solver's inner loop (cost model in docs/benchmarks.md). Both are written with explicit
// two-lane double vectors (GCC/Clang vector extensions: SSE2 natively, wasm simd128 under Emscripten), so
// they do not depend on the auto-vectoriser, which handled the old 4-row register blocks poorly in wasm (a
// 6-column forward pass took 28 ms at n = 50k, m = 300). One row of W at a time against up to 6 columns:
//   multiply:           vectorised along the row (two W entries against two entries of each P column, P
//                       being column-major already), 6 accumulators summed across lanes at the row end;
//   multiply_transpose: the row added into each output column (an axpy along the row, no reduction).
// Measured (wasm, n = 49614, m = 300, float64, ms, old 4-row blocks -> this): 3-column forward 13.4 -> 5.2-6,
// transposed 13 -> 6.6-7.5; 6 columns 28-30 -> 9-12 and 17 -> 12. Blocks of 2-4 rows were slower in wasm
// (more live vector registers than V8 keeps in registers) and natively. Accumulation is in double whatever
// the storage type; no -ffast-math needed.
constexpr int kChunk = 6;  // columns per pass over W

typedef double f64x2 __attribute__((vector_size(16)));
typedef float f32x2 __attribute__((vector_size(8)));

inline f64x2 load2(const double* p) {
  f64x2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline f64x2 load2(const float* p) {
  f32x2 v;
  std::memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, f64x2);
}
inline void store2(double* p, f64x2 v) { std::memcpy(p, &v, sizeof v); }

// out[c][i] = W.row(i) . P[c] for every row i and c < K.
template <int K, typename T>
void forward_chunk(const T* W, int n, int m, const double* const* P, double* const* out) {
  for (int i = 0; i < n; ++i) {
    const T* row = W + static_cast<std::size_t>(i) * m;
    f64x2 acc[K];
    for (int c = 0; c < K; ++c) acc[c] = f64x2{0.0, 0.0};
    int j = 0;
    for (; j + 2 <= m; j += 2) {
      const f64x2 w = load2(row + j);
      for (int c = 0; c < K; ++c) acc[c] += w * load2(P[c] + j);
    }
    for (int c = 0; c < K; ++c) {
      double sum = acc[c][0] + acc[c][1];
      if (j < m) sum += static_cast<double>(row[j]) * P[c][j];
      out[c][i] = sum;
    }
  }
}

// out[c] += R[c][i] W.row(i) for every row i and c < K.
template <int K, typename T>
void transpose_chunk(const T* W, int n, int m, const double* const* R, double* const* out) {
  for (int i = 0; i < n; ++i) {
    const T* row = W + static_cast<std::size_t>(i) * m;
    f64x2 coef[K];
    for (int c = 0; c < K; ++c) coef[c] = f64x2{R[c][i], R[c][i]};
    int j = 0;
    for (; j + 2 <= m; j += 2) {
      const f64x2 w = load2(row + j);
      for (int c = 0; c < K; ++c) store2(out[c] + j, load2(out[c] + j) + w * coef[c]);
    }
    if (j < m)
      for (int c = 0; c < K; ++c) out[c][j] += R[c][i] * static_cast<double>(row[j]);
  }
}

// Runs kernel<K> over the columns of A (into those of out) in chunks of at most kChunk columns.
template <template <int, typename> class Kernel, typename T>
void by_chunks(const T* W, int n, int m, const Eigen::MatrixXd& A, Eigen::MatrixXd& out) {
  const int k = static_cast<int>(A.cols());
  for (int c0 = 0; c0 < k; c0 += kChunk) {
    const int kc = std::min(kChunk, k - c0);
    const double* a[kChunk];
    double* o[kChunk];
    for (int c = 0; c < kc; ++c) {
      a[c] = A.col(c0 + c).data();
      o[c] = out.col(c0 + c).data();
    }
    switch (kc) {
      case 1: Kernel<1, T>::run(W, n, m, a, o); break;
      case 2: Kernel<2, T>::run(W, n, m, a, o); break;
      case 3: Kernel<3, T>::run(W, n, m, a, o); break;
      case 4: Kernel<4, T>::run(W, n, m, a, o); break;
      case 5: Kernel<5, T>::run(W, n, m, a, o); break;
      default: Kernel<6, T>::run(W, n, m, a, o); break;
    }
  }
}

template <int K, typename T>
struct Forward {
  static void run(const T* W, int n, int m, const double* const* P, double* const* out) { forward_chunk<K>(W, n, m, P, out); }
};
template <int K, typename T>
struct Transpose {
  static void run(const T* W, int n, int m, const double* const* R, double* const* out) { transpose_chunk<K>(W, n, m, R, out); }
};

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
    by_chunks<Forward>(values32_.data(), rows_, cols_, P, out);
  else
    by_chunks<Forward>(values64_.data(), rows_, cols_, P, out);
}

void WeightMatrix::multiply_transpose(const Eigen::MatrixXd& R, Eigen::MatrixXd& out) const {
  if (R.rows() != rows_)
    throw Error("W^T * R: R has " + std::to_string(R.rows()) + " rows, W has " + std::to_string(rows_) + " rows");
  out.setZero(cols_, R.cols());
  if (single_)
    by_chunks<Transpose>(values32_.data(), rows_, cols_, R, out);
  else
    by_chunks<Transpose>(values64_.data(), rows_, cols_, R, out);
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
