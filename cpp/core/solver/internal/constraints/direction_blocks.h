// Several directions side by side, one block of 3 columns (x, y, z) per direction: the hard constraints' restoring
// directions (#V or m rows by 3K). Their axis views gather one coordinate of every direction without a copy, so a
// combination of the directions is three matrix products instead of K updates of the whole block.
#pragma once

#include <Eigen/Core>

namespace sd {

// Columns axis, axis + 3, axis + 6, ... of R: rows by R.cols() / 3.
inline Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>> axis_columns(const Eigen::MatrixXd& R, int axis) {
  return {R.data() + axis * R.rows(), R.rows(), R.cols() / 3, Eigen::OuterStride<>(3 * R.rows())};
}
inline Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>> axis_columns(Eigen::MatrixXd& R, int axis) {
  return {R.data() + axis * R.rows(), R.rows(), R.cols() / 3, Eigen::OuterStride<>(3 * R.rows())};
}

}  // namespace sd
