#include "core/solver/internal/steps/constrained_step.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <sstream>

#include "core/error.h"

namespace sd {

namespace {

[[noreturn]] void throw_not_positive_definite(const Eigen::MatrixXd& S, const char* matrix) {
  std::ostringstream message;
  message << "hard constraints: C^T " << matrix << "^-1 C (" << S.rows() << " x " << S.cols()
          << ") is not positive definite: the constraints' gradients (the volume or its parts, the skeleton's "
             "lengths and middles) are linearly dependent in the space of the step, or the pose is far beyond the "
             "model's size (use fewer or larger parts, fewer bones, or more modes / cage vertices)";
  throw Error(ErrorCode::NumericalFailure, message.str());
}

}  // namespace

Eigen::VectorXd solve_schur(const Eigen::MatrixXd& S, const Eigen::VectorXd& rhs, const char* matrix) {
  if (S.rows() == 1) {
    const double s = S(0, 0);
    if (!(s > 0.0) || !std::isfinite(s)) {
      std::ostringstream message;
      message << "volume constraint: c^T " << matrix << "^-1 c = " << s
              << " is not positive (the volume gradient is orthogonal to the space of the step)";
      throw Error(ErrorCode::NumericalFailure, message.str());
    }
    return Eigen::VectorXd::Constant(1, rhs[0] / s);
  }
  // Equilibrated first (unit diagonal): the constraints' rows scale differently with the model's units (the
  // volume's gradient as length^2, a bone's rows not at all), so without it the pivot test below refused a
  // skeleton in millimetres that it took in metres.
  const Eigen::VectorXd diagonal = S.diagonal();
  if (!S.allFinite() || !(diagonal.minCoeff() > 0.0)) throw_not_positive_definite(S, matrix);
  const Eigen::VectorXd scale = diagonal.cwiseSqrt().cwiseInverse();
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(scale.asDiagonal() * S * scale.asDiagonal());
  const Eigen::VectorXd d = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || !(d.minCoeff() > 1e-14 * d.cwiseAbs().maxCoeff()))
    throw_not_positive_definite(S, matrix);
  return scale.asDiagonal() * ldlt.solve(scale.asDiagonal() * rhs);
}

Eigen::MatrixXd block_products(const Eigen::MatrixXd& C, const Eigen::MatrixXd& Z) {
  // One block each (the global volume): the very reduction the scalar code did, so K = 1 stays bit-identical.
  if (C.cols() == 3 && Z.cols() == 3) return Eigen::MatrixXd::Constant(1, 1, block_dot(C, Z));
  const Eigen::Index K = C.cols() / 3, s = Z.cols() / 3;
  Eigen::MatrixXd out(K, s);
  for (Eigen::Index k = 0; k < K; ++k)
    for (Eigen::Index t = 0; t < s; ++t) out(k, t) = C.middleCols(3 * k, 3).cwiseProduct(Z.middleCols(3 * t, 3)).sum();
  return out;
}

Eigen::MatrixXd add_blocks(const Eigen::MatrixXd& a, const Eigen::MatrixXd& B, const Eigen::VectorXd& x) {
  Eigen::MatrixXd out = a;
  for (Eigen::Index k = 0; k < x.size(); ++k) out += x[k] * B.middleCols(3 * k, 3);
  return out;
}

double multiplier_dot(const Eigen::VectorXd& lambda, const Eigen::VectorXd& g) {
  if (lambda.size() == 0) return 0.0;
  double sum = lambda[0] * g[0];
  for (Eigen::Index k = 1; k < lambda.size(); ++k) sum += lambda[k] * g[k];
  return sum;
}

Eigen::VectorXd volume_multipliers(const Eigen::MatrixXd& u, const Eigen::MatrixXd& V, const Eigen::MatrixXd& C,
                                   const Eigen::VectorXd& g) {
  const Eigen::VectorXd rhs = g - block_products(C, u).col(0);
  return solve_schur(block_products(C, V), rhs, "A");
}

Eigen::VectorXd start_constraint(const Eigen::VectorXd& g, const Eigen::VectorXd& scales) {
  bool negligible = true;
  for (Eigen::Index k = 0; k < g.size(); ++k)
    negligible = negligible && !(std::abs(g[k]) > kNegligibleVolumeError * scales[k]);
  return negligible ? Eigen::VectorXd::Zero(g.size()) : g;
}

}  // namespace sd
