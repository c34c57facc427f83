// The explicit two-lane products (two_lane_kernels.h) against Eigen's: odd sizes (a lane left over), blocks of 1 to
// 7 columns (a group of three left partly empty), and a matrix that is not square.
#include "core/solver/internal/two_lane_kernels.h"

#include <gtest/gtest.h>

namespace sd {
namespace {

TEST(TwoLaneKernels, MatrixTimesBlockIsTheProduct) {
  for (const auto& [rows, inner] : {std::pair<int, int>{7, 7}, {391, 391}, {10, 5}, {1, 1}}) {
    const Eigen::MatrixXd A = Eigen::MatrixXd::Random(rows, inner);
    for (int columns = 1; columns <= 7; ++columns) {
      const Eigen::MatrixXd V = Eigen::MatrixXd::Random(inner, columns);
      const Eigen::MatrixXd expected = A * V;
      EXPECT_LE((two_lane::matrix_times_block(A, V) - expected).cwiseAbs().maxCoeff(),
                1e-13 * (1.0 + expected.cwiseAbs().maxCoeff()))
          << rows << " x " << inner << " times " << columns << " columns";
    }
  }
}

}  // namespace
}  // namespace sd
