#include "core/basis/internal/block_ldlt.h"

#include <Eigen/OrderingMethods>
#include <vector>

#include "core/error.h"

namespace sd {
namespace {

// Entries below the diagonal of the Cholesky factor of the symmetric pattern `full` (both triangles stored):
// row k of L holds the nodes met walking the elimination tree up from each i < k in column k of the pattern,
// each counted once per row (the up-looking symbolic factorization). O(entries of L) time, O(n) memory.
double count_factor_entries(const Eigen::SparseMatrix<double>& full) {
  const int n = static_cast<int>(full.cols());
  std::vector<int> parent(n, -1), mark(n, -1);
  double entries = 0;
  for (int k = 0; k < n; ++k) {
    mark[k] = k;
    for (Eigen::SparseMatrix<double>::InnerIterator it(full, k); it; ++it) {
      int i = static_cast<int>(it.row());
      if (i >= k) continue;
      for (; mark[i] != k; i = parent[i]) {
        if (parent[i] == -1) parent[i] = k;
        entries += 1;
        mark[i] = k;
      }
    }
  }
  return entries;
}

}  // namespace

BlockLdlt::BlockLdlt(const Eigen::SparseMatrix<double>& lower) {
  Eigen::AMDOrdering<int> ordering;
  ordering(lower.selfadjointView<Eigen::Lower>(), inverse_);
  permutation_ = inverse_.inverse();
  permuted_ = lower.selfadjointView<Eigen::Lower>().twistedBy(permutation_);
  factor_nonzeros_ = count_factor_entries(permuted_);
}

void BlockLdlt::factorize() {
  factor_.compute(permuted_);
  permuted_ = Eigen::SparseMatrix<double>();
  if (factor_.info() != Eigen::Success || !(factor_.vectorD().array() > 0).all())
    throw Error(ErrorCode::NumericalFailure, "harmonic coordinates: the grid Laplacian could not be factored");
}

void BlockLdlt::solve_in_place(Block& X) const {
  const int n = rows();
  Block Y(n, X.cols());
  for (int i = 0; i < n; ++i) Y.row(permutation_.indices()[i]) = X.row(i);
  // L holds the entries below the unit diagonal, column by column.
  const auto& L = factor_.matrixL().nestedExpression();
  const int* start = L.outerIndexPtr();
  const int* row = L.innerIndexPtr();
  const double* value = L.valuePtr();
  for (int j = 0; j < n; ++j)
    for (int p = start[j]; p < start[j + 1]; ++p) Y.row(row[p]) -= value[p] * Y.row(j);
  const Eigen::VectorXd& D = factor_.vectorD();
  for (int j = 0; j < n; ++j) Y.row(j) /= D[j];
  for (int j = n - 1; j >= 0; --j)
    for (int p = start[j]; p < start[j + 1]; ++p) Y.row(j) -= value[p] * Y.row(row[p]);
  for (int i = 0; i < n; ++i) X.row(i) = Y.row(permutation_.indices()[i]);
}

}  // namespace sd
