// Preconditioned conjugate gradients on several symmetric positive (semi)definite systems A x_t = r_t
// run in lockstep, so that one application of A serves all of them. In the fast subspace step every
// application of A = W^T J_f^T J_f W streams the dense W twice; batching x, y, z and the volume
// right-hand side makes that cost independent of their number (design.md section 4).
//
// Each system's vector is an m by 3 block; s systems are the columns 3t .. 3t+2 of an m by 3s matrix.
// The iteration starts from x = 0 (so every iterate is a descent direction of its quadratic) and stops a
// system when its preconditioned residual sqrt(r.z) has dropped by the relative tolerance.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace sd {

struct PcgOperator {
  // AP = A P and image = W P for a block of search directions P (m by 3a). The image lets the caller
  // accumulate W x without another pass over W (for the full space, image = P).
  std::function<void(const Eigen::MatrixXd& P, Eigen::MatrixXd& AP, Eigen::MatrixXd& image)> apply;
  // Z = M^-1 R for a block R (m by 3a): the preconditioner, applied column by column.
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd& R)> precondition;
};

class BatchedPcg {
 public:
  // rhs: m by 3s; image_rows: rows of the image of a block (#V for W, m for the identity).
  BatchedPcg(PcgOperator op, const Eigen::MatrixXd& rhs, Eigen::Index image_rows);

  // Iterates until every system's relative preconditioned residual is <= tolerance or `max_products`
  // more applications of A have been spent. May be called again with a tighter tolerance to continue.
  void run(double tolerance, int max_products);
  // Iterates every system until `done(*this)` holds (checked after each product) or the budget is spent:
  // for callers whose accuracy requirement is on a combination of the solutions.
  void run_until(const std::function<bool(const BatchedPcg&)>& done, int max_products);

  int systems() const { return static_cast<int>(rz0_.size()); }
  const Eigen::MatrixXd& x() const { return x_; }          // m by 3s
  const Eigen::MatrixXd& image() const { return image_; }  // W x, image_rows by 3s
  // M^-1 r_t (the first search direction) and its image W M^-1 r_t (zero image until the first product).
  const Eigen::MatrixXd& first_direction() const { return first_direction_; }
  const Eigen::MatrixXd& first_direction_image() const { return first_image_; }
  bool first_image_valid(int t) const { return first_image_valid_[t]; }
  int products() const { return products_; }
  const Eigen::MatrixXd& residual() const { return r_; }         // r_t - A x_t
  const Eigen::MatrixXd& preconditioned() const { return z_; }   // M^-1 (r_t - A x_t)
  double relative_residual(int t) const;
  bool converged(double tolerance) const;

 private:
  PcgOperator op_;
  Eigen::MatrixXd x_, r_, z_, p_, image_, first_direction_, first_image_;
  std::vector<double> rz_, rz0_;
  std::vector<bool> broken_, first_image_valid_;
  void iterate(const std::vector<Eigen::Index>& active);
  int products_ = 0;
};

}  // namespace sd
