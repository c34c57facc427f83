// Non-negative least squares (nnls.h): the coordinate descent reaches the KKT point of small problems, and the
// greedy selection recovers a sparse non-negative combination.
#include "core/solver/internal/reduced/nnls.h"

#include <gtest/gtest.h>

#include "core/solver/internal/reduced/training_poses.h"

namespace sd {
namespace {

Eigen::MatrixXd random_matrix(int rows, int cols, unsigned seed) {
  PortableRandom random(seed);
  Eigen::MatrixXd A(rows, cols);
  for (Eigen::Index k = 0; k < A.size(); ++k) A.data()[k] = random.gaussian();
  return A;
}

// KKT conditions of min |A w - b| over w >= 0: w >= 0, gradient g = A^T (A w - b) >= 0, w_j g_j = 0.
TEST(Nnls, SatisfiesTheKktConditions) {
  const Eigen::MatrixXd A = random_matrix(40, 15, 3);
  const Eigen::VectorXd b = random_matrix(40, 1, 4).col(0);
  const Eigen::VectorXd w = nonnegative_least_squares(A, b);
  const Eigen::VectorXd g = A.transpose() * (A * w - b);
  const double scale = (A.transpose() * b).cwiseAbs().maxCoeff();
  int active = 0;
  for (Eigen::Index j = 0; j < w.size(); ++j) {
    EXPECT_GE(w[j], 0.0);
    EXPECT_GE(g[j], -1e-9 * scale);
    EXPECT_LE(std::abs(w[j] * g[j]), 1e-9 * scale * (1.0 + w.cwiseAbs().maxCoeff()));
    active += w[j] == 0.0;
  }
  EXPECT_GT(active, 0) << "a random right-hand side should make some bounds active";
}

// b built from 5 columns with positive weights: the greedy fit finds a combination that matches it.
TEST(Nnls, GreedyRecoversASparseNonNegativeCombination) {
  const Eigen::MatrixXd A = random_matrix(60, 200, 5).cwiseAbs();
  Eigen::VectorXd truth = Eigen::VectorXd::Zero(200);
  for (int j : {7, 31, 64, 120, 199}) truth[j] = 0.5 + 0.1 * j / 200.0;
  const Eigen::VectorXd b = A * truth;
  const NnlsFit fit = greedy_nnls(A, b, 60, 1e-8);
  EXPECT_LE(fit.relative_error, 1e-6);
  EXPECT_LE(fit.columns.size(), 60u);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(200);
  for (size_t k = 0; k < fit.columns.size(); ++k) {
    EXPECT_GT(fit.weights[static_cast<Eigen::Index>(k)], 0.0);
    w[fit.columns[k]] = fit.weights[static_cast<Eigen::Index>(k)];
  }
  EXPECT_LE((A * w - b).norm(), 1e-6 * b.norm());
}

}  // namespace
}  // namespace sd
