// The 3x3-block matrix against the same matrix as an Eigen sparse matrix, on a random pattern with
// rows of different lengths and a vertex with no blocks.
#include "core/solver/internal/block_sparse3.h"

#include <gtest/gtest.h>

#include <random>


namespace sd {
namespace {

std::shared_ptr<const BlockPattern> random_pattern(int n, std::mt19937& rng) {
  auto p = std::make_shared<BlockPattern>();
  std::uniform_int_distribution<int> count(0, 6), vertex(0, n - 1);
  for (int i = 0; i < n; ++i) {
    p->row_start.push_back(static_cast<int>(p->column.size()));
    const int k = i == 3 ? 0 : count(rng);
    if (k > 0) p->column.push_back(i);
    for (int t = 1; t < k; ++t) p->column.push_back(vertex(rng));
  }
  p->row_start.push_back(static_cast<int>(p->column.size()));
  return p;
}

TEST(BlockSparse3, SparseMatrixHoldsTheBlocks) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  const int n = 40;
  BlockSparse3 A(random_pattern(n, rng));
  for (int k = 0; k < A.pattern().block_count(); ++k)
    for (int e = 0; e < 9; ++e) A.block(k)[e] = normal(rng);
  const Eigen::MatrixXd S = Eigen::MatrixXd(A.to_sparse());
  ASSERT_EQ(S.rows(), 3 * n);
  ASSERT_EQ(S.cols(), 3 * n);
  // Every block where its pattern puts it (a column repeated in one row adds up), nothing elsewhere.
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  const BlockPattern& p = A.pattern();
  for (int i = 0; i < n; ++i)
    for (int k = p.row_start[i]; k < p.row_start[i + 1]; ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) expected(3 * i + r, 3 * p.column[k] + c) += A.block(k)[3 * r + c];
  EXPECT_LE((S - expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(S.middleRows(9, 3).norm(), 0.0) << "a row without blocks";
}

}  // namespace
}  // namespace sd
