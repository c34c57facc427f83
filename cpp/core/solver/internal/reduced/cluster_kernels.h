// The two small products every rotation-cluster operation is made of (rotation_clusters.h): a cluster's 3 x m rows
// times an m x 3 block, and an m x 3 block plus the rows' transpose times a 3 x 3 matrix. They run once per cluster
// per product, hundreds of times per iteration, so they are written with explicit two-lane double vectors (GCC/Clang
// vector extensions: SSE2 natively, wasm simd128 under Emscripten, as the W kernels of basis_matrix.cpp): Eigen's
// products of such thin blocks neither vectorise in wasm nor avoid copying the rows.
#pragma once

#include <Eigen/Core>
#include <cstring>

namespace sd::cluster_kernels {

typedef double f64x2 __attribute__((vector_size(16)));

inline f64x2 load2(const double* p) {
  f64x2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store2(double* p, f64x2 v) { std::memcpy(p, &v, sizeof v); }

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

}  // namespace sd::cluster_kernels
