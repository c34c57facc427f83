#include "core/basis/basis_matrix.h"

#include <gtest/gtest.h>

#include <random>

#include "core/error.h"

namespace sd {
namespace {

// A BasisMatrix filled with random values and the same values in a dense matrix (rounded to float
// when single precision, so the dense products are the exact reference for the stored values).
BasisMatrix random_matrix(int n, int m, bool single, Eigen::MatrixXd& dense, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  BasisMatrix W(n, m, single);
  dense.resize(n, m);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      double v = uniform(rng);
      if (single) v = static_cast<double>(static_cast<float>(v));
      W.set(i, j, v);
      dense(i, j) = v;
    }
  return W;
}

TEST(BasisMatrix, StorageSizeAndAccess) {
  BasisMatrix W64(7, 5, false), W32(7, 5, true);
  EXPECT_EQ(W64.bytes(), 7u * 5u * 8u);
  EXPECT_EQ(W32.bytes(), 7u * 5u * 4u);
  W64.set(6, 4, 0.1);
  W32.set(6, 4, 0.1);
  EXPECT_EQ(W64.get(6, 4), 0.1);
  EXPECT_EQ(W32.get(6, 4), static_cast<double>(0.1f));
  Eigen::RowVectorXd row = Eigen::RowVectorXd::LinSpaced(5, 1, 5);
  W64.set_row(2, row);
  EXPECT_EQ(W64.to_dense().row(2), row);
  EXPECT_EQ(static_cast<const double*>(W64.data())[2 * 5 + 3], 4.0);  // row-major
}

// Products against Eigen's dense products for every column count the solver uses (and more, to cover
// the chunking over 4 columns), for row counts that are and are not multiples of the 4-row blocking.
TEST(BasisMatrix, ProductsMatchDenseProducts) {
  for (bool single : {false, true})
    for (int n : {1, 4, 13, 64})
      for (int m : {1, 3, 4, 9, 37})
        for (int k : {1, 2, 3, 4, 5, 9}) {
          Eigen::MatrixXd dense;
          BasisMatrix W = random_matrix(n, m, single, dense, 17u * n + m);
          Eigen::MatrixXd P = Eigen::MatrixXd::Random(m, k), R = Eigen::MatrixXd::Random(n, k), out;
          W.multiply(P, out);
          ASSERT_EQ(out.rows(), n);
          ASSERT_EQ(out.cols(), k);
          // Double accumulation of the same terms in another order: agreement to a few ulps of the sum.
          EXPECT_LE((out - dense * P).cwiseAbs().maxCoeff(), 1e-14 * m) << "n " << n << " m " << m << " k " << k;
          W.multiply_transpose(R, out);
          ASSERT_EQ(out.rows(), m);
          ASSERT_EQ(out.cols(), k);
          EXPECT_LE((out - dense.transpose() * R).cwiseAbs().maxCoeff(), 1e-14 * n)
              << "n " << n << " m " << m << " k " << k;
        }
}

// The solver's blocks have 5-8 columns (x, y, z for two right-hand sides, plus the volume gradient):
// multiply sweeps each row once for 4 columns and once for the tail, so every k in 5..8 takes a
// different path. Widths m around the 4-wide inner unrolling, float64 and float32.
TEST(BasisMatrix, WideBlocksMatchDenseProducts) {
  for (bool single : {false, true})
    for (int m : {5, 8, 31, 300})
      for (int k = 5; k <= 8; ++k) {
        const int n = 203;
        Eigen::MatrixXd dense;
        BasisMatrix W = random_matrix(n, m, single, dense, 31u * m + k);
        const Eigen::MatrixXd P = Eigen::MatrixXd::Random(m, k), R = Eigen::MatrixXd::Random(n, k);
        Eigen::MatrixXd out;
        W.multiply(P, out);
        ASSERT_EQ(out.rows(), n);
        ASSERT_EQ(out.cols(), k);
        EXPECT_LE((out - dense * P).cwiseAbs().maxCoeff(), 1e-14 * m)
            << "m " << m << " k " << k << " single " << single;
        W.multiply_transpose(R, out);
        ASSERT_EQ(out.rows(), m);
        ASSERT_EQ(out.cols(), k);
        EXPECT_LE((out - dense.transpose() * R).cwiseAbs().maxCoeff(), 1e-14 * n)
            << "m " << m << " k " << k << " single " << single;
      }
}

TEST(BasisMatrix, ProductsRejectMismatchedShapes) {
  BasisMatrix W(4, 3, false);
  Eigen::MatrixXd out;
  EXPECT_THROW(W.multiply(Eigen::MatrixXd::Zero(4, 2), out), Error);
  EXPECT_THROW(W.multiply_transpose(Eigen::MatrixXd::Zero(3, 2), out), Error);
}

}  // namespace
}  // namespace sd
