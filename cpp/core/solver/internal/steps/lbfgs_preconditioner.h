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
#include <algorithm>
#include <functional>

namespace sd {

class LbfgsPreconditioner {
 public:
  explicit LbfgsPreconditioner(int capacity = 8) : capacity_(std::max(capacity, 0)) {}

  // Keeps the newest `capacity` pairs. Skips a pair whose curvature s.y is not positive and finite. O(capacity
  // size) per pair (its inner products with the others).
  void add_pair(const Eigen::MatrixXd& s, const Eigen::MatrixXd& y);
  void clear();
  // Changes the capacity, dropping the oldest pairs beyond it (0: H is the base preconditioner).
  void resize(int capacity);
  int size() const { return count_; }

  // H r, the two-loop recursion's in matrix form (see the .cpp), with base(q) as the initial inverse (H = base
  // without pairs), for each block of r (its columns in threes, rows as the pairs'; base gets them all at once).
  Eigen::MatrixXd apply(const Eigen::MatrixXd& r,
                        const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& base) const;

 private:
  // The slot of the i-th oldest pair.
  int slot_of(int i) const { return (oldest_ + i) % capacity_; }
  // Rows (one per pair) from slot order to age order (oldest first), and back.
  Eigen::MatrixXd by_age(const Eigen::MatrixXd& by_slot) const;
  Eigen::MatrixXd by_slot(const Eigen::MatrixXd& by_age) const;

  int capacity_;
  // The pairs as columns (a block flattened), in slots taken in turn: S_ and Y_ have capacity_ columns once a
  // pair came, the first count_ of them filled.
  Eigen::MatrixXd S_, Y_;
  // U_(i, j) = s_i . y_j for i <= j, the pairs by age (oldest first): the upper triangle, its diagonal 1 / rho.
  Eigen::MatrixXd U_;
  int count_ = 0;
  int oldest_ = 0;  // the oldest pair's slot
};

}  // namespace sd
