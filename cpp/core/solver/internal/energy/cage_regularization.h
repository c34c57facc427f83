// The cage regularisation of the subspace problem (docs/method.md section 6.1):
//   R(P) = 1/2 eps tr(P^T H P),   H = (I - Pi) S (I - Pi),   S = tau^2 (G^2 + tau^2 I)^-1,   G = W^T W,
// added to the energy in the cage subspace only. Pi projects onto the affine maps of the rest cage (the
// columns 1, x0, y0, z0 of P0), so rigid and affine motions of the cage cost nothing; S is close to the
// identity on the cage motions that barely move the mesh (eigenvalues lambda of G far below tau) and close to
// 0 on those that move it ((tau / lambda)^2: the square keeps the filter sharp, so a poorly conditioned but
// sound cage such as the hand bones' (smallest lambda 3e-4 of the largest) is barely touched), so the term
// damps just the near-null directions of W.
// Why: such directions (a cage region far from the mesh, or combinations of cage vertices that cancel inside
// it) are otherwise nearly free: the minimizer may move them far for a negligible gain, so the cow's cage
// grows from a diagonal of 42 to 543 on a 5% head pull while the mesh looks fine. With the term they follow
// the cage's best affine fit, and the mesh of a cage without such directions moves by a negligible amount
// (tests/cpp/solver/internal/energy/cage_regularization_test.cpp).
// Scales: tau = kWeakEigenvalue x the largest eigenvalue of G; eps = relative weight x trace(B) / m, with
// B = (L W)^T (L W) the mesh energy's Hessian in the cage unknowns, so the weight does not depend on the
// model's size, scale or cage resolution.
#pragma once

#include <Eigen/Core>

namespace sd {

class CageRegularization {
 public:
  // Eigenvalues of G below this fraction of its largest count as near-null cage motions.
  static constexpr double kWeakEigenvalue = 1e-5;

  CageRegularization() = default;
  // `G` = W^T W (m by m); `rest` = P0 (m by 3); `hessian_scale` = trace(B) (m by m).
  CageRegularization(const Eigen::MatrixXd& G, const Eigen::MatrixXd& rest, double hessian_scale);

  // Sets the relative weight (SolverOptions::cage_regularization); returns whether eps changed (never
  // without a cage: eps stays 0).
  bool set_relative_weight(double relative);
  bool active() const { return eps_ > 0; }
  double eps() const { return eps_; }

  double energy(const Eigen::MatrixXd& P) const;                  // R(P)
  Eigen::MatrixXd gradient(const Eigen::MatrixXd& P) const;       // eps H P, m by 3
  Eigen::MatrixXd hessian_times(const Eigen::MatrixXd& V) const;  // eps H V, m by s
  const Eigen::MatrixXd& penalty() const { return H_; }           // H (without eps)

 private:
  Eigen::MatrixXd H_;
  double unit_ = 0;  // trace(B) / m: eps per unit of relative weight
  double eps_ = 0;
};

}  // namespace sd
