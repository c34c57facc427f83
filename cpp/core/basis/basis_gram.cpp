#include "core/basis/basis_gram.h"

#include <algorithm>

#include "core/parallel/parallel_for.h"

namespace sd {

Eigen::MatrixXd basis_gram(const BasisMatrix& W, int stride, int rows) {
  const int m = W.cols();
  constexpr int kChunk = 256;  // rows per rank update
  Eigen::MatrixXd G = parallel::parallel_reduce(
      0, rows, 1024, Eigen::MatrixXd(Eigen::MatrixXd::Zero(m, m)),
      [&](int lo, int hi) {
        Eigen::MatrixXd part = Eigen::MatrixXd::Zero(m, m);
        Eigen::MatrixXd R(kChunk, m);
        for (int k0 = lo; k0 < hi; k0 += kChunk) {
          const int count = std::min(hi, k0 + kChunk) - k0;
          for (int k = 0; k < count; ++k)
            for (int j = 0; j < m; ++j) R(k, j) = W.get((k0 + k) * stride, j);
          part.selfadjointView<Eigen::Lower>().rankUpdate(R.topRows(count).transpose());
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
