// R^T R for a tall matrix R given by blocks of rows, so R is never held whole; deterministic for any thread count.
#pragma once

#include <Eigen/Core>
#include <algorithm>

#include "core/parallel/parallel_for.h"

namespace sd {

// R^T R (cols x cols, both triangles) for a tall R given by rows(lo, hi) (rows lo .. hi - 1, at most
// kGramChunk at a time). Fixed blocks of rows each sum their own R_b^T R_b (lower triangle, rank updates) and the
// partials are added in block order: the result does not depend on the thread count. At most 16 blocks (of at
// least `min_block` rows) bound the partials' memory to 16 x cols^2.
constexpr int kGramChunk = 512;
template <typename Rows>
Eigen::MatrixXd row_gram(int row_count, int cols, Rows&& rows, int min_block = 4096) {
  const int block = std::max(min_block, (row_count + 15) / 16);
  Eigen::MatrixXd G = parallel::parallel_reduce(
      0, row_count, block, Eigen::MatrixXd(Eigen::MatrixXd::Zero(cols, cols)),
      [&](int lo, int hi) {
        Eigen::MatrixXd part = Eigen::MatrixXd::Zero(cols, cols);
        for (int r0 = lo; r0 < hi; r0 += kGramChunk) {
          const Eigen::MatrixXd R = rows(r0, std::min(hi, r0 + kGramChunk));
          part.selfadjointView<Eigen::Lower>().rankUpdate(R.transpose());
        }
        return part;
      },
      [](Eigen::MatrixXd a, const Eigen::MatrixXd& b) {
        a += b;
        return a;
      });
  return G.selfadjointView<Eigen::Lower>();
}

}  // namespace sd
