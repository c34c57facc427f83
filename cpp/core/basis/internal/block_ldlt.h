// A sparse symmetric positive definite matrix factored once, A = P^T L D L^T P (an up-looking LDL^T, the
// algorithm of Davis' LDL and of Eigen's simplicial LDL^T, after a fill-reducing AMD ordering P), then solved
// for many right-hand sides in blocks: each block of k columns, stored row by row, streams the factor once
// (k-wide row updates that vectorise), instead of once per column.
// The factor's size and the factorization's work are known after the ordering and a symbolic pass, before the
// factor is allocated, so a caller can refuse a grid too large for its memory or time budget first; the
// factorization reports its progress row by row, so a caller can cancel it.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <vector>

namespace sd {

class BlockLdlt {
 public:
  using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  // Orders A (its lower triangle is read) and counts the factor's entries per column; allocates O(nonzeros
  // of A).
  explicit BlockLdlt(const Eigen::SparseMatrix<double>& lower);

  // Entries of L below the diagonal, and the bytes the numeric factor will hold (values, row indices and the
  // per-row work arrays).
  double factor_nonzeros() const { return factor_nonzeros_; }
  double factor_bytes() const { return factor_nonzeros_ * (sizeof(double) + sizeof(int)) + 48.0 * rows(); }
  // Multiply-adds of the numeric factorization: sum over the columns of L of (entries)^2 / 2 + entries.
  double factor_work() const { return factor_work_; }
  int rows() const { return static_cast<int>(permutation_.size()); }

  // Throws sd::Error (NumericalFailure) when A is not positive definite. `progress` (optional) is called with
  // the fraction of factor_work() done, every kProgressWork multiply-adds or so; it may throw to stop.
  static constexpr double kProgressWork = 2e7;
  void factorize(const std::function<void(double)>& progress = {});

  // X := A^-1 X for a block of right-hand sides (rows() x k). The same bits whatever else runs at the time.
  void solve_in_place(Block& X) const;

 private:
  Eigen::SparseMatrix<double> permuted_;  // P A P^T, both triangles (until factorize)
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation_, inverse_;
  std::vector<int> parent_;       // the elimination tree
  std::vector<long long> start_;  // L's columns: start_[j] .. start_[j + 1]
  std::vector<int> row_;          // L's row indices, column by column
  std::vector<double> value_;     // L's entries below its unit diagonal
  Eigen::VectorXd diagonal_;      // D
  double factor_nonzeros_ = 0, factor_work_ = 0;
};

}  // namespace sd
