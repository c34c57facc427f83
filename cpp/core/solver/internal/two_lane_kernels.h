// Small dense products that run many times per Gauss-Newton iteration, written with explicit two-lane double
// vectors (GCC/Clang vector extensions: SSE2 natively, wasm simd128 under Emscripten, as the W kernels of
// basis_matrix.cpp): Eigen 3.4 has no wasm vector backend, and its products of thin blocks copy (pack) their
// operands first. The rotation clusters' products are made of two of them (rotation_clusters.h): a cluster's 3 x m
// rows times an m x 3 block, and an m x 3 block plus the rows' transpose times a 3 x 3 matrix. The third, an m x m
// matrix times m x 3 blocks, applies the subspace's constant matrices (the Laplacian Gram B, the handles' Gram, the
// cage regulariser) in each reduced product: in wasm 1.6-3 times faster than Eigen's product (measured at m = 391).
// The last two, a float32 row dotted with a double vector and a scaled float32 row taken off one, solve the factor
// preconditioner's packed float32 Cholesky factor (packed_factor.h).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstring>

namespace sd::two_lane {

typedef double f64x2 __attribute__((vector_size(16)));

inline f64x2 load2(const double* p) {
  f64x2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store2(double* p, f64x2 v) { std::memcpy(p, &v, sizeof v); }
// Two float32 entries, widened to double.
inline f64x2 load2(const float* p) {
  float f[2];
  std::memcpy(f, p, sizeof f);
  return f64x2{f[0], f[1]};
}

// sum_j a[j] x[j] over j < n, a in float32, x and the sum in double (the packed factor's rows: packed_factor.h).
inline double dot(const float* a, const double* x, Eigen::Index n) {
  f64x2 even{0.0, 0.0}, odd{0.0, 0.0};
  Eigen::Index j = 0;
  for (; j + 4 <= n; j += 4) {
    even += load2(a + j) * load2(x + j);
    odd += load2(a + j + 2) * load2(x + j + 2);
  }
  for (; j + 2 <= n; j += 2) even += load2(a + j) * load2(x + j);
  const f64x2 sum = even + odd;
  double out = sum[0] + sum[1];
  for (; j < n; ++j) out += static_cast<double>(a[j]) * x[j];
  return out;
}

// x[j] -= s a[j] over j < n, a in float32.
inline void subtract_scaled(const float* a, double s, double* x, Eigen::Index n) {
  const f64x2 scale{s, s};
  Eigen::Index j = 0;
  for (; j + 2 <= n; j += 2) store2(x + j, load2(x + j) - load2(a + j) * scale);
  for (; j < n; ++j) x[j] -= s * static_cast<double>(a[j]);
}

// rows (3 x m, row-major, contiguous) times V (m x 3, column-major with leading dimension ld).
inline Eigen::Matrix3d rows_times(const double* rows, Eigen::Index m, const double* V, Eigen::Index ld) {
  f64x2 acc[9];
  for (f64x2& a : acc) a = f64x2{0.0, 0.0};
  Eigen::Index j = 0;
  for (; j + 2 <= m; j += 2) {
    const f64x2 r[3] = {load2(rows + j), load2(rows + m + j), load2(rows + 2 * m + j)};
    const f64x2 v[3] = {load2(V + j), load2(V + ld + j), load2(V + 2 * ld + j)};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) acc[3 * a + b] += r[a] * v[b];
  }
  Eigen::Matrix3d out;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double sum = acc[3 * a + b][0] + acc[3 * a + b][1];
      if (j < m) sum += rows[a * m + j] * V[b * ld + j];
      out(a, b) = sum;
    }
  return out;
}

// out (m x 3, column-major with leading dimension ld) += rows^T C for rows 3 x m (row-major, contiguous).
inline void add_rows_transpose_times(const double* rows, Eigen::Index m, const Eigen::Matrix3d& C, double* out,
                                     Eigen::Index ld) {
  f64x2 c[9];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) c[3 * a + b] = f64x2{C(a, b), C(a, b)};
  Eigen::Index j = 0;
  for (; j + 2 <= m; j += 2) {
    const f64x2 r[3] = {load2(rows + j), load2(rows + m + j), load2(rows + 2 * m + j)};
    for (int b = 0; b < 3; ++b)
      store2(out + b * ld + j, load2(out + b * ld + j) + r[0] * c[b] + r[1] * c[3 + b] + r[2] * c[6 + b]);
  }
  if (j < m)
    for (int b = 0; b < 3; ++b)
      out[b * ld + j] += rows[j] * C(0, b) + rows[m + j] * C(1, b) + rows[2 * m + j] * C(2, b);
}

// A V for A (r x m, column-major) and V (m x c, column-major), c a multiple of 3 or not: column j of A is added into
// each output column, scaled by V's row j, so that A is read once per three columns of V and nothing is copied.
inline Eigen::MatrixXd matrix_times_block(const Eigen::MatrixXd& A, const Eigen::MatrixXd& V) {
  const Eigen::Index r = A.rows(), m = A.cols(), c = V.cols();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(r, c);
  for (Eigen::Index first = 0; first < c; first += 3) {
    const Eigen::Index width = std::min<Eigen::Index>(3, c - first);
    double* o[3] = {out.data() + first * r, out.data() + std::min(first + 1, c - 1) * r,
                    out.data() + std::min(first + 2, c - 1) * r};
    for (Eigen::Index j = 0; j < m; ++j) {
      const double* a = A.data() + j * r;
      double v[3] = {0.0, 0.0, 0.0};
      for (Eigen::Index k = 0; k < width; ++k) v[k] = V(j, first + k);
      const f64x2 s[3] = {f64x2{v[0], v[0]}, f64x2{v[1], v[1]}, f64x2{v[2], v[2]}};
      Eigen::Index i = 0;
      for (; i + 2 <= r; i += 2) {
        const f64x2 x = load2(a + i);
        for (Eigen::Index k = 0; k < width; ++k) store2(o[k] + i, load2(o[k] + i) + x * s[k]);
      }
      for (; i < r; ++i)
        for (Eigen::Index k = 0; k < width; ++k) o[k][i] += a[i] * v[k];
    }
  }
  return out;
}

}  // namespace sd::two_lane
