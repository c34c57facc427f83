#include "core/basis/basis_matrix.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel/parallel_for.h"

namespace sd {
namespace {

// The two products are the solver's inner loop (cost model in docs/benchmarks.md). Both are written with explicit
// two-lane double vectors (GCC/Clang vector extensions: SSE2 natively, wasm simd128 under Emscripten), so
// they do not depend on the auto-vectoriser, which vectorises blocks of rows poorly in wasm. One row of W at a
// time against up to 6 columns (blocks of 2-4 rows keep more vectors live than V8 keeps in registers; the
// measurements are in docs/benchmarks.md, "The W kernels"):
//   multiply:           vectorised along the row (two W entries against two entries of each P column, P
//                       being column-major already), 6 accumulators summed across lanes at the row end;
//   multiply_transpose: the row added into each output column (an axpy along the row, no reduction).
// Accumulation is in double whatever the storage type; no -ffast-math needed.
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

// Runs Kernel<K> over `rows` rows of W (starting at `row`) for the k columns in[c] -> out[c], in chunks
// of at most kChunk columns (one stream over those rows per chunk).
template <template <int, typename> class Kernel, typename T>
void by_chunks(const T* W, int row, int rows, int m, int k, const double* const* in, double* const* out) {
  const T* block = W + static_cast<std::size_t>(row) * m;
  for (int c0 = 0; c0 < k; c0 += kChunk) {
    const int kc = std::min(kChunk, k - c0);
    const double* const* a = in + c0;
    double* const* o = out + c0;
    switch (kc) {
      case 1: Kernel<1, T>::run(block, rows, m, a, o); break;
      case 2: Kernel<2, T>::run(block, rows, m, a, o); break;
      case 3: Kernel<3, T>::run(block, rows, m, a, o); break;
      case 4: Kernel<4, T>::run(block, rows, m, a, o); break;
      case 5: Kernel<5, T>::run(block, rows, m, a, o); break;
      default: Kernel<6, T>::run(block, rows, m, a, o); break;
    }
  }
}

template <int K, typename T>
struct Forward {
  static void run(const T* W, int n, int m, const double* const* P, double* const* out) {
    forward_chunk<K>(W, n, m, P, out);
  }
};
template <int K, typename T>
struct Transpose {
  static void run(const T* W, int n, int m, const double* const* R, double* const* out) {
    transpose_chunk<K>(W, n, m, R, out);
  }
};

// Threads (cpp/core/parallel). The forward pass writes each output row from one row of W, so any split of
// the rows gives the same bits; blocks of about 64k entries of W (512 KB in float64) are worth a task.
// The transposed pass sums over all rows: each fixed block of kTransposeRows rows sums into its own
// m x k partial, and the partials are added in block order, so the result does not depend on the thread
// count (a range of one block is the plain serial loop). The partials cost blocks x m x k doubles, under
// 1% of the bytes of W that the pass streams.
constexpr int kTransposeRows = 1024;
int forward_rows(int m) { return std::max(64, (1 << 16) / std::max(m, 1)); }

template <typename T>
void multiply_rows(const T* W, int n, int m, const Eigen::MatrixXd& P, Eigen::MatrixXd& out) {
  const int k = static_cast<int>(P.cols());
  parallel::parallel_for(0, n, forward_rows(m), [&](int lo, int hi) {
    std::vector<const double*> in(k);
    std::vector<double*> o(k);
    for (int c = 0; c < k; ++c) {
      in[c] = P.col(c).data();
      o[c] = out.col(c).data() + lo;
    }
    by_chunks<Forward>(W, lo, hi - lo, m, k, in.data(), o.data());
  });
}

template <typename T>
void multiply_transpose_rows(const T* W, int n, int m, const Eigen::MatrixXd& R, Eigen::MatrixXd& out) {
  const int k = static_cast<int>(R.cols());
  const int blocks = parallel::block_count(0, n, kTransposeRows);
  auto run_block = [&](int b, double* const* o) {
    const int lo = b * kTransposeRows, rows = std::min(n, lo + kTransposeRows) - lo;
    std::vector<const double*> in(k);
    for (int c = 0; c < k; ++c) in[c] = R.col(c).data() + lo;
    by_chunks<Transpose>(W, lo, rows, m, k, in.data(), o);
  };
  std::vector<double*> o(k);
  if (blocks <= 1) {
    for (int c = 0; c < k; ++c) o[c] = out.col(c).data();
    if (blocks == 1) run_block(0, o.data());
    return;
  }
  const std::size_t stride = static_cast<std::size_t>(m) * k;  // one block's partial, m x k column-major
  std::vector<double> partial(stride * blocks, 0.0);
  parallel::parallel_for(0, blocks, 1, [&](int lo, int hi) {
    std::vector<double*> po(k);
    for (int b = lo; b < hi; ++b) {
      for (int c = 0; c < k; ++c) po[c] = partial.data() + stride * b + static_cast<std::size_t>(m) * c;
      run_block(b, po.data());
    }
  });
  // out = sum of the partials in block order, entry by entry (any split of the entries is exact).
  double* result = out.data();  // m x k column-major, contiguous like each partial
  parallel::parallel_for(0, static_cast<int>(stride), 4096, [&](int lo, int hi) {
    for (int e = lo; e < hi; ++e) {
      double sum = 0.0;
      for (int b = 0; b < blocks; ++b) sum += partial[stride * b + e];
      result[e] = sum;
    }
  });
}

}  // namespace

BasisMatrix::BasisMatrix(int rows, int cols, bool single_precision)
    : rows_(rows), cols_(cols), single_(single_precision) {
  if (rows < 0 || cols < 0) throw Error("weight matrix: negative size");
  const std::size_t count = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  if (single_) values32_.assign(count, 0.0f);
  else values64_.assign(count, 0.0);
}

std::size_t BasisMatrix::bytes() const {
  return single_ ? values32_.size() * sizeof(float) : values64_.size() * sizeof(double);
}

double BasisMatrix::get(int i, int j) const {
  assert(i >= 0 && i < rows_ && j >= 0 && j < cols_);
  const std::size_t at = static_cast<std::size_t>(i) * cols_ + j;
  return single_ ? static_cast<double>(values32_[at]) : values64_[at];
}

void BasisMatrix::set(int i, int j, double value) {
  assert(i >= 0 && i < rows_ && j >= 0 && j < cols_);
  const std::size_t at = static_cast<std::size_t>(i) * cols_ + j;
  if (single_) values32_[at] = static_cast<float>(value);
  else values64_[at] = value;
}

void BasisMatrix::set_row(int i, const Eigen::RowVectorXd& row) {
  assert(i >= 0 && i < rows_ && row.size() == cols_);
  const std::size_t at = static_cast<std::size_t>(i) * cols_;
  if (single_)
    for (int j = 0; j < cols_; ++j) values32_[at + j] = static_cast<float>(row[j]);
  else std::copy(row.data(), row.data() + cols_, values64_.begin() + static_cast<std::ptrdiff_t>(at));
}

void BasisMatrix::multiply(const Eigen::MatrixXd& P, Eigen::MatrixXd& out) const {
  if (P.rows() != cols_)
    throw Error("W * P: P has " + std::to_string(P.rows()) + " rows, W has " + std::to_string(cols_) + " columns");
  out.resize(rows_, P.cols());
  if (single_) multiply_rows(values32_.data(), rows_, cols_, P, out);
  else multiply_rows(values64_.data(), rows_, cols_, P, out);
}

void BasisMatrix::multiply_transpose(const Eigen::MatrixXd& R, Eigen::MatrixXd& out) const {
  if (R.rows() != rows_)
    throw Error("W^T * R: R has " + std::to_string(R.rows()) + " rows, W has " + std::to_string(rows_) + " rows");
  out.setZero(cols_, R.cols());
  if (single_) multiply_transpose_rows(values32_.data(), rows_, cols_, R, out);
  else multiply_transpose_rows(values64_.data(), rows_, cols_, R, out);
}

Eigen::MatrixXd BasisMatrix::to_dense() const {
  Eigen::MatrixXd dense(rows_, cols_);
  for (int i = 0; i < rows_; ++i)
    for (int j = 0; j < cols_; ++j) dense(i, j) = get(i, j);
  return dense;
}

BasisMatrix BasisMatrix::select_rows(const std::vector<int>& rows) const {
  BasisMatrix out(static_cast<int>(rows.size()), cols_, single_);
  const std::size_t m = static_cast<std::size_t>(cols_);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const int i = rows[r];
    if (i < 0 || i >= rows_)
      throw Error("weight matrix: row " + std::to_string(i) + " outside [0, " + std::to_string(rows_) + ")");
    const std::size_t from = static_cast<std::size_t>(i) * m, to = r * m;
    if (single_) std::copy_n(values32_.begin() + from, m, out.values32_.begin() + to);
    else std::copy_n(values64_.begin() + from, m, out.values64_.begin() + to);
  }
  return out;
}

int BasisMatrix::passes(int columns) { return (columns + kChunk - 1) / kChunk; }

const void* BasisMatrix::data() const {
  return single_ ? static_cast<const void*>(values32_.data()) : static_cast<const void*>(values64_.data());
}

}  // namespace sd
