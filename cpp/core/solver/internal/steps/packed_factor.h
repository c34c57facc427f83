// The factor preconditioner's Cholesky factor L (gauss_newton_factor.h), kept in float32, its rows packed, and
// solved in double.
//
// Why: each PCG iteration applies P^-1 = (L L^T)^-1 once or more, and a 3m x 3m factor in double is read whole
// (twice a triangle) each time: 8.4 MB on the hand bones (3m = 1026), about as many bytes as their W. Eigen's
// triangular solve of one vector reads its full-width columns, runs on one thread and, in wasm, without vectors.
// Here L is rounded to float32 once (half the bytes of a triangle: 2.1 MB there) and solved with double
// accumulation: the operator is exactly (L~ L~^T)^-1 for the rounded L~, symmetric positive definite like P
// (rounding moves L's entries by 6e-8 of themselves, the preconditioner's quality by about that times P's
// condition number), so PCG's guarantees hold.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace sd {

class PackedFactor {
 public:
  PackedFactor() = default;
  // From the lower triangle of L (n x n, positive diagonal).
  explicit PackedFactor(const Eigen::MatrixXd& L);
  Eigen::Index size() const { return n_; }
  // Whether every rounded entry is finite and every rounded diagonal entry positive (a factor of a matrix whose
  // scale float32 cannot hold is not: the caller keeps N).
  bool valid() const { return valid_; }
  // x := (L~ L~^T)^-1 x for x of size(): forward substitution with L~, then back substitution with L~^T.
  void solve_in_place(double* x) const;

 private:
  const float* row(Eigen::Index i) const { return rows_.data() + i * (i + 1) / 2; }
  Eigen::Index n_ = 0;
  std::vector<float> rows_;               // row i of L~: entries 0 .. i, from offset i (i + 1) / 2
  std::vector<double> inverse_diagonal_;  // 1 / L~(i, i), in double
  bool valid_ = false;
};

}  // namespace sd
