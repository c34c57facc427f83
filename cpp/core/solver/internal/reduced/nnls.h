// Greedy non-negative least squares for choosing cubature samples (An, Kim and James 2008, "Optimizing cubature
// for efficient integration of subspace deformations", section 4): columns of A are candidates, b the target;
// repeatedly add the candidates most positively correlated with the residual and refit non-negative weights on
// the chosen ones. The weights of the chosen columns are found by cyclic coordinate descent on the normal
// equations, warm-started from the previous round: the problem is a convex quadratic over w >= 0, and each sweep
// costs O(k^2) for k chosen columns, so hundreds of columns refit in milliseconds.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace sd {

struct NnlsFit {
  std::vector<int> columns;   // the chosen columns of A with a positive weight, increasing
  Eigen::VectorXd weights;    // their weights (> 0)
  double relative_error = 0;  // |A_S w - b| / |b|
};

// Chooses at most max_columns columns, stopping early once the relative error is at most `tolerance`.
NnlsFit greedy_nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, int max_columns, double tolerance);

// min |A w - b| over w >= 0 for a small dense A, by the same coordinate descent (for tests and the refits).
Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace sd
