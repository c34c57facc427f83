// A sparse symmetric positive definite matrix factored once, A = P^T L D L^T P (Eigen's simplicial LDL^T after
// a fill-reducing AMD ordering P), then solved for many right-hand sides in blocks: each block of k columns,
// stored row by row, streams the factor once (k-wide row updates that vectorise), instead of once per column.
// The factor's size is known after the ordering and a symbolic pass, before the factor is allocated, so a
// caller can refuse a grid too large for its memory budget first.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace sd {

class BlockLdlt {
 public:
  using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  // Orders A (its lower triangle is read) and counts the factor's entries; allocates O(nonzeros of A).
  explicit BlockLdlt(const Eigen::SparseMatrix<double>& lower);

  // Entries of L below the diagonal, and the bytes the numeric factor will hold (values and row indices).
  double factor_nonzeros() const { return factor_nonzeros_; }
  double factor_bytes() const { return factor_nonzeros_ * (sizeof(double) + sizeof(int)) + 32.0 * rows(); }
  int rows() const { return static_cast<int>(permutation_.size()); }

  // Throws sd::Error (NumericalFailure) when A is not positive definite.
  void factorize();

  // X := A^-1 X for a block of right-hand sides (rows() x k). The same bits whatever else runs at the time.
  void solve_in_place(Block& X) const;

 private:
  Eigen::SparseMatrix<double> permuted_;  // P A P^T, both triangles (until factorize)
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation_, inverse_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> factor_;
  double factor_nonzeros_ = 0;
};

}  // namespace sd
