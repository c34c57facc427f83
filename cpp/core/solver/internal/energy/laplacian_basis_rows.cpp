#include "core/solver/internal/energy/laplacian_basis_rows.h"

namespace sd {

void add_scaled_row(const BasisMatrix& W, int j, double s, double* out) {
  const int m = W.cols();
  if (W.single_precision()) {
    const float* row = static_cast<const float*>(W.data()) + static_cast<std::size_t>(j) * m;
    for (int k = 0; k < m; ++k) out[k] += s * static_cast<double>(row[k]);
  } else {
    const double* row = static_cast<const double*>(W.data()) + static_cast<std::size_t>(j) * m;
    for (int k = 0; k < m; ++k) out[k] += s * row[k];
  }
}

Eigen::MatrixXd laplacian_rows_times_w(const Eigen::SparseMatrix<double, Eigen::RowMajor>& L, const BasisMatrix& W,
                                       int r0, int rows) {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> out =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>::Zero(rows, W.cols());
  for (int i = 0; i < rows; ++i)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(L, r0 + i); it; ++it)
      add_scaled_row(W, static_cast<int>(it.col()), it.value(), out.row(i).data());
  return out;
}

}  // namespace sd
