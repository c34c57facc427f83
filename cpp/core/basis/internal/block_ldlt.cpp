#include "core/basis/internal/block_ldlt.h"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <vector>

#include "core/error.h"

namespace sd {

// The symbolic factorization (up-looking): row k of L holds the nodes met walking the elimination tree up from
// each i < k in column k of the pattern, each counted once per row. O(entries of L) time, O(n) memory.
BlockLdlt::BlockLdlt(const Eigen::SparseMatrix<double>& lower) {
  Eigen::AMDOrdering<int> ordering;
  ordering(lower.selfadjointView<Eigen::Lower>(), inverse_);
  permutation_ = inverse_.inverse();
  permuted_ = lower.selfadjointView<Eigen::Lower>().twistedBy(permutation_);
  const int n = static_cast<int>(permuted_.cols());
  parent_.assign(n, -1);
  std::vector<int> mark(n, -1);
  std::vector<long long> count(n, 0);
  for (int k = 0; k < n; ++k) {
    mark[k] = k;
    for (Eigen::SparseMatrix<double>::InnerIterator it(permuted_, k); it; ++it) {
      int i = static_cast<int>(it.row());
      if (i >= k) continue;
      for (; mark[i] != k; i = parent_[i]) {
        if (parent_[i] == -1) parent_[i] = k;
        ++count[i];
        mark[i] = k;
      }
    }
  }
  start_.assign(static_cast<size_t>(n) + 1, 0);
  for (int j = 0; j < n; ++j) {
    start_[j + 1] = start_[j] + count[j];
    factor_work_ += 0.5 * double(count[j]) * double(count[j]) + double(count[j]);
  }
  factor_nonzeros_ = double(start_[n]);
}

// Davis' LDL numeric factorization: row k of L from a sparse triangular solve with the rows above, whose
// pattern is the elimination tree's reach of column k of A.
void BlockLdlt::factorize(const std::function<void(double)>& progress) {
  const int n = rows();
  row_.resize(static_cast<size_t>(factor_nonzeros_));
  value_.resize(static_cast<size_t>(factor_nonzeros_));
  diagonal_.resize(n);
  std::vector<double> y(n, 0.0);
  std::vector<int> pattern(n), flag(n, -1);
  std::vector<long long> filled(start_.begin(), start_.end() - 1);  // next free slot per column
  double work = 0, reported = 0;
  for (int k = 0; k < n; ++k) {
    int top = n;
    flag[k] = k;
    for (Eigen::SparseMatrix<double>::InnerIterator it(permuted_, k); it; ++it) {
      int i = static_cast<int>(it.row());
      if (i > k) continue;
      y[i] += it.value();
      int length = 0;
      for (; flag[i] != k; i = parent_[i]) {
        pattern[length++] = i;
        flag[i] = k;
      }
      while (length > 0) pattern[--top] = pattern[--length];
    }
    double d = y[k];
    y[k] = 0;
    for (; top < n; ++top) {
      const int i = pattern[top];
      const double yi = y[i];
      y[i] = 0;
      const long long end = filled[i];
      for (long long p = start_[i]; p < end; ++p) y[row_[p]] -= value_[p] * yi;
      work += double(end - start_[i]) + 1;
      const double l = yi / diagonal_[i];
      d -= l * yi;
      row_[end] = k;
      value_[end] = l;
      filled[i] = end + 1;
    }
    if (!(d > 0))
      throw Error(ErrorCode::NumericalFailure, "harmonic coordinates: the grid Laplacian could not be factored");
    diagonal_[k] = d;
    if (progress && work - reported >= kProgressWork) {
      reported = work;
      progress(factor_work_ > 0 ? std::min(1.0, work / factor_work_) : 1.0);
    }
  }
  permuted_ = Eigen::SparseMatrix<double>();
}

void BlockLdlt::solve_in_place(Block& X) const {
  const int n = rows();
  Block Y(n, X.cols());
  for (int i = 0; i < n; ++i) Y.row(permutation_.indices()[i]) = X.row(i);
  // L holds the entries below its unit diagonal, column by column.
  for (int j = 0; j < n; ++j)
    for (long long p = start_[j]; p < start_[j + 1]; ++p) Y.row(row_[p]) -= value_[p] * Y.row(j);
  for (int j = 0; j < n; ++j) Y.row(j) /= diagonal_[j];
  for (int j = n - 1; j >= 0; --j)
    for (long long p = start_[j]; p < start_[j + 1]; ++p) Y.row(j) -= value_[p] * Y.row(row_[p]);
  for (int i = 0; i < n; ++i) X.row(i) = Y.row(permutation_.indices()[i]);
}

}  // namespace sd
