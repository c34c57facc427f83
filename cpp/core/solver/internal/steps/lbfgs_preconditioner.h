// A preconditioner that learns from the previous Gauss-Newton steps' conjugate-gradient products:
// the limited-memory BFGS inverse built from pairs (s, y = A s) on top of a base preconditioner
// (Morales and Nocedal 2000, "Automatic preconditioning by limited memory quasi-Newton updating").
//
// Consecutive Gauss-Newton matrices A = W^T J_f^T J_f W differ little (J_f changes with the rotations of the
// Laplacian coordinates only), so the pairs of the last solve satisfy H y = s almost exactly for the next
// one: the directions CG already explored no longer need products. The base N^-1 lacks exactly the
// rotation terms of A, which is what the pairs supply. H stays symmetric positive definite when every pair
// has s.y > 0 (others are skipped). Blocks are m by 3; dot products are over all entries.
#pragma once

#include <Eigen/Core>
#include <deque>
#include <functional>

namespace sd {

class LbfgsPreconditioner {
 public:
  explicit LbfgsPreconditioner(int capacity = 8) : capacity_(capacity) {}

  // Keeps the newest `capacity` pairs. Skips a pair whose curvature s.y is not positive and finite.
  void add_pair(const Eigen::MatrixXd& s, const Eigen::MatrixXd& y);
  void clear() { pairs_.clear(); }
  // Changes the capacity, dropping the oldest pairs beyond it (0: H is the base preconditioner).
  void resize(int capacity);
  int size() const { return static_cast<int>(pairs_.size()); }

  // H r by the two-loop recursion, with base(q) as the initial inverse (H = base without pairs), for each block
  // of r (its columns in threes; base gets them all at once).
  Eigen::MatrixXd apply(const Eigen::MatrixXd& r,
                        const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& base) const;

 private:
  struct Pair {
    Eigen::MatrixXd s, y;
    double rho;  // 1 / s.y
  };
  int capacity_;
  std::deque<Pair> pairs_;  // oldest first
};

}  // namespace sd
