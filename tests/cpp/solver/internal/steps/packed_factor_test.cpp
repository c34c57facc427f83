// The factor preconditioner's float32 Cholesky factor (packed_factor.h): its solve is exactly the inverse of
// L~ L~^T for the rounded factor L~ (so symmetric positive definite, as PCG needs), and within float32 rounding
// times the condition number of the double factor's solve.
#include "core/solver/internal/steps/packed_factor.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

namespace sd {
namespace {

Eigen::MatrixXd random_spd(int n, double condition, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd G(n, n);
  for (Eigen::Index i = 0; i < G.size(); ++i) G.data()[i] = normal(rng);
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(G).householderQ();
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d[i] = n == 1 ? 1.0 : std::pow(condition, double(i) / (n - 1));
  return Q * d.asDiagonal() * Q.transpose();
}

Eigen::VectorXd solved(const PackedFactor& f, Eigen::VectorXd x) {
  f.solve_in_place(x.data());
  return x;
}

TEST(PackedFactor, SolvesTheRoundedFactorExactlyAndTheFactorCloselyAndSymmetrically) {
  for (const int n : {1, 2, 7, 64, 131}) {  // odd and even rows: the two-lane kernels' tails
    const Eigen::MatrixXd P = random_spd(n, 1e3, 3 + n);
    const Eigen::LLT<Eigen::MatrixXd> llt(P);
    ASSERT_EQ(llt.info(), Eigen::Success);
    const PackedFactor f(llt.matrixLLT());
    ASSERT_EQ(f.size(), n);
    const Eigen::MatrixXd L = Eigen::MatrixXd(llt.matrixL()).cast<float>().cast<double>();  // L~
    const Eigen::MatrixXd rounded = L * L.transpose();
    std::mt19937 rng(n);
    std::normal_distribution<double> normal;
    Eigen::VectorXd b(n), c(n);
    for (int i = 0; i < n; ++i) {
      b[i] = normal(rng);
      c[i] = normal(rng);
    }
    const Eigen::VectorXd x = solved(f, b), y = solved(f, c);
    EXPECT_LE((rounded * x - b).norm(), 1e-12 * b.norm() * 1e3) << "n = " << n << ": (L~ L~^T)^-1 b";
    EXPECT_LE((x - llt.solve(b)).norm(), 1e-7 * 1e3 * llt.solve(b).norm()) << "n = " << n << ": close to P^-1 b";
    EXPECT_NEAR(c.dot(x), b.dot(y), 1e-12 * std::abs(c.dot(x)) + 1e-14) << "n = " << n << ": symmetric";
    EXPECT_GT(b.dot(x), 0.0) << "n = " << n << ": positive definite";
    EXPECT_TRUE(f.valid());
  }
  // A factor whose scale float32 cannot hold is refused, not solved into infinities.
  EXPECT_FALSE(PackedFactor(Eigen::MatrixXd::Identity(3, 3) * 1e-50).valid());
  EXPECT_FALSE(PackedFactor(Eigen::MatrixXd::Identity(3, 3) * 1e50).valid());
}

}  // namespace
}  // namespace sd
