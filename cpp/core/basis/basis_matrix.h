// Dense n by m matrix W of cage coordinates (X = W P), stored row-major in float64 or float32.
// float32 halves the bytes the solver streams per product; the products accumulate in double.
// The products are memory-bound (cost model in docs/benchmarks.md): each call reads W exactly once, so callers batch
// several right-hand sides as columns (x, y, z and the volume gradient) into one call.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace sd {

class BasisMatrix {
 public:
  BasisMatrix() = default;
  BasisMatrix(int rows, int cols, bool single_precision);

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  bool single_precision() const { return single_; }
  std::size_t bytes() const;

  double get(int i, int j) const;
  void set(int i, int j, double value);
  void set_row(int i, const Eigen::RowVectorXd& row);

  // out (n by k) = W * P (m by k).
  void multiply(const Eigen::MatrixXd& P, Eigen::MatrixXd& out) const;
  // out (m by k) = W^T * R (n by k).
  void multiply_transpose(const Eigen::MatrixXd& R, Eigen::MatrixXd& out) const;
  // The whole matrix in double (for tests, exact mode and export). n by m.
  Eigen::MatrixXd to_dense() const;
  // The given rows (in that order) as a matrix of their own, in the same precision: the rows a few sampled
  // vertices need, which a reduced solve multiplies without streaming the whole of W.
  BasisMatrix select_rows(const std::vector<int>& rows) const;

  // How many streams over W one multiply or multiply_transpose with this many columns takes (columns go in
  // chunks of 6 per stream).
  static int passes(int columns);

  // Pointer to the row-major data (float or double by single_precision()); for export without a copy.
  const void* data() const;

 private:
  int rows_ = 0;
  int cols_ = 0;
  bool single_ = false;
  std::vector<double> values64_;
  std::vector<float> values32_;
};

}  // namespace sd
