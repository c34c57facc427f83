#include "core/solver/internal/energy/cage_regularization.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include <cmath>

#include "core/solver/internal/two_lane_kernels.h"

namespace sd {
namespace {

// The largest eigenvalue of a symmetric positive semidefinite matrix, by power iteration (to a few digits:
// it only sets the scale tau).
double largest_eigenvalue(const Eigen::MatrixXd& G) {
  Eigen::VectorXd v = Eigen::VectorXd::Ones(G.rows()).normalized();
  double lambda = 0;
  for (int k = 0; k < 100; ++k) {
    const Eigen::VectorXd Gv = G * v;
    const double next = v.dot(Gv);
    const double norm = Gv.norm();
    if (norm == 0) return 0;
    v = Gv / norm;
    if (std::abs(next - lambda) <= 1e-6 * next) return next;
    lambda = next;
  }
  return lambda;
}

// I - Pi: removes the affine maps of the rest cage (span of 1, x0, y0, z0).
Eigen::MatrixXd remove_affine(const Eigen::MatrixXd& rest) {
  const Eigen::Index m = rest.rows();
  Eigen::MatrixXd A(m, 4);
  A << Eigen::VectorXd::Ones(m), rest;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(m, 4);
  return Eigen::MatrixXd::Identity(m, m) - Q * Q.transpose();
}

}  // namespace

CageRegularization::CageRegularization(const Eigen::MatrixXd& G, const Eigen::MatrixXd& rest, double hessian_scale) {
  const Eigen::Index m = G.rows();
  const double tau = kWeakEigenvalue * largest_eigenvalue(G);
  if (!(tau > 0) || !(hessian_scale > 0) || m <= 4) return;  // no scale: stays off
  Eigen::MatrixXd shifted = G * G;
  shifted.diagonal().array() += tau * tau;
  const Eigen::LLT<Eigen::MatrixXd> factor(shifted);  // G^2 + tau^2 I is positive definite
  const Eigen::MatrixXd S = (tau * tau) * factor.solve(Eigen::MatrixXd::Identity(m, m));
  const Eigen::MatrixXd free_of_affine = remove_affine(rest);
  H_ = free_of_affine * S * free_of_affine;
  H_ = 0.5 * (H_ + H_.transpose()).eval();  // symmetric to the bit, for the Cholesky factors that add it
  unit_ = hessian_scale / static_cast<double>(m);
}

bool CageRegularization::set_relative_weight(double relative) {
  const double previous = eps_;
  eps_ = relative * unit_;
  return eps_ != previous;
}

double CageRegularization::energy(const Eigen::MatrixXd& P) const {
  if (!active()) return 0.0;
  return 0.5 * eps_ * (P.transpose() * H_ * P).trace();
}

Eigen::MatrixXd CageRegularization::gradient(const Eigen::MatrixXd& P) const {
  if (!active()) return Eigen::MatrixXd::Zero(P.rows(), P.cols());
  return eps_ * two_lane::matrix_times_block(H_, P);
}

Eigen::MatrixXd CageRegularization::hessian_times(const Eigen::MatrixXd& V) const {
  if (!active()) return Eigen::MatrixXd::Zero(V.rows(), V.cols());
  return eps_ * two_lane::matrix_times_block(H_, V);
}

}  // namespace sd
