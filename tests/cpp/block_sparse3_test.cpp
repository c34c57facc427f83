// The 3x3-block matrix against the same matrix as an Eigen sparse matrix, on a random pattern with
// rows of different lengths and a vertex with no blocks.
#include "core/block_sparse3.h"

#include <gtest/gtest.h>

#include <random>

#include "core/deformation_energy.h"
#include "core/error.h"

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

TEST(BlockSparse3, ProductsMatchTheSparseMatrix) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  const int n = 40;
  BlockSparse3 A(random_pattern(n, rng));
  for (int k = 0; k < A.pattern().block_count(); ++k)
    for (int e = 0; e < 9; ++e) A.block(k)[e] = normal(rng);
  const Eigen::SparseMatrix<double> S = A.to_sparse();
  Eigen::MatrixXd x(n, 6);  // two vectors of x, y, z
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = normal(rng);
  const Eigen::MatrixXd Sx = deinterleave(S * interleave(x));
  const Eigen::MatrixXd Stx = deinterleave(Eigen::MatrixXd(S.transpose()) * interleave(x));
  EXPECT_LE((A.multiply(x) - Sx).cwiseAbs().maxCoeff(), 1e-12 * Sx.cwiseAbs().maxCoeff());
  EXPECT_LE((A.multiply_transpose(x) - Stx).cwiseAbs().maxCoeff(), 1e-12 * Stx.cwiseAbs().maxCoeff());
  EXPECT_EQ(A.multiply(x).row(3).norm(), 0.0) << "a row without blocks";
}

TEST(BlockSparse3, RejectsABlockOfTheWrongShape) {
  std::mt19937 rng(6);
  const BlockSparse3 A(random_pattern(10, rng));
  EXPECT_THROW(A.multiply(Eigen::MatrixXd::Zero(9, 3)), Error);
  EXPECT_THROW(A.multiply_transpose(Eigen::MatrixXd::Zero(10, 4)), Error);
}

}  // namespace
}  // namespace sd
