#include "core/basis/internal/block_ldlt.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <random>
#include <vector>

#include "core/error.h"

namespace sd {
namespace {

// The 7-point Laplacian of an n^3 grid plus a positive diagonal shift at random nodes (a grid whose border
// touches Dirichlet values): symmetric positive definite, like the harmonic coordinates' matrix.
Eigen::SparseMatrix<double> grid_matrix(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(0.0, 3.0);
  auto id = [n](int i, int j, int k) { return (k * n + j) * n + i; };
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int u = id(i, j, k);
        t.emplace_back(u, u, 6.0 + shift(rng));
        if (i > 0) t.emplace_back(u, id(i - 1, j, k), -1.0);
        if (j > 0) t.emplace_back(u, id(i, j - 1, k), -1.0);
        if (k > 0) t.emplace_back(u, id(i, j, k - 1), -1.0);
      }
  Eigen::SparseMatrix<double> lower(n * n * n, n * n * n);
  lower.setFromTriplets(t.begin(), t.end());
  return lower;
}

TEST(BlockLdlt, SolvesBlocksOfRightHandSides) {
  const Eigen::SparseMatrix<double> lower = grid_matrix(9, 1);
  BlockLdlt factor(lower);
  factor.factorize();
  const Eigen::SparseMatrix<double> A = lower.selfadjointView<Eigen::Lower>();
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 13);
  BlockLdlt::Block X = B;
  factor.solve_in_place(X);
  EXPECT_LE((A * Eigen::MatrixXd(X) - B).cwiseAbs().maxCoeff(), 1e-12);
  // The same as Eigen's own solve of the same factor, column by column.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> reference(A);
  EXPECT_LE((Eigen::MatrixXd(X) - reference.solve(B)).cwiseAbs().maxCoeff(), 1e-12);
}

// The symbolic count, known before the factor is allocated, is the factor's size.
TEST(BlockLdlt, CountsTheFactorBeforeAllocatingIt) {
  for (int n : {4, 7, 10}) {
    const Eigen::SparseMatrix<double> lower = grid_matrix(n, 2);
    BlockLdlt factor(lower);
    const double counted = factor.factor_nonzeros();
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> reference(lower.selfadjointView<Eigen::Lower>());
    // Eigen's L (AMD ordering as here) holds the same entries below its unit diagonal.
    EXPECT_EQ(counted, static_cast<double>(reference.matrixL().nestedExpression().nonZeros())) << n;
    EXPECT_GT(factor.factor_bytes(), counted * 8);
  }
}

// The factorization reports the fraction of its counted work done, rising to 1, and a report that throws stops
// it there.
TEST(BlockLdlt, ReportsProgressThroughTheFactorization) {
  const Eigen::SparseMatrix<double> lower = grid_matrix(22, 3);
  BlockLdlt factor(lower);
  ASSERT_GT(factor.factor_work(), 4 * BlockLdlt::kProgressWork);
  std::vector<double> seen;
  factor.factorize([&](double fraction) { seen.push_back(fraction); });
  ASSERT_GE(seen.size(), 3u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_GT(seen.back(), 0.7);
  EXPECT_LE(seen.back(), 1.0);
  BlockLdlt stopped(lower);
  int calls = 0;
  EXPECT_THROW(stopped.factorize([&](double) {
    if (++calls == 2) throw Error(ErrorCode::Cancelled, "stop");
  }),
               Error);
  EXPECT_EQ(calls, 2);
}

TEST(BlockLdlt, RefusesAMatrixThatIsNotPositiveDefinite) {
  Eigen::SparseMatrix<double> lower(2, 2);
  lower.insert(0, 0) = 1;
  lower.insert(1, 0) = 2;
  lower.insert(1, 1) = 1;
  BlockLdlt factor(lower);
  EXPECT_THROW(factor.factorize(), Error);
}

}  // namespace
}  // namespace sd
