// The 3x3-block matrix against the same matrix as an Eigen sparse matrix, on a random pattern with
// rows of different lengths and a vertex with no blocks.
#include "core/solver/internal/steps/block_sparse3.h"

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

TEST(BlockPattern, ColumnIndexListsEveryBlockOnceByIncreasingRow) {
  std::mt19937 rng(7);
  BlockPattern p = *random_pattern(40, rng);
  p.index_columns();
  ASSERT_EQ(static_cast<int>(p.column_start.size()), p.vertex_count() + 1);
  std::vector<int> seen(p.block_count(), 0);
  for (int j = 0; j < p.vertex_count(); ++j)
    for (int s = p.column_start[j]; s < p.column_start[j + 1]; ++s) {
      const int k = p.column_blocks[s];
      ++seen[k];
      EXPECT_EQ(p.column[k], j);
      EXPECT_EQ(p.column_rows[s], p.row[k]);
      EXPECT_GE(k, p.row_start[p.row[k]]);
      EXPECT_LT(k, p.row_start[p.row[k] + 1]);
      if (s > p.column_start[j]) EXPECT_LE(p.row[p.column_blocks[s - 1]], p.row[k]) << "rows increase";
    }
  for (int k = 0; k < p.block_count(); ++k) EXPECT_EQ(seen[k], 1) << "block " << k;
}

}  // namespace
}  // namespace sd
