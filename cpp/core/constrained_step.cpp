#include "core/constrained_step.h"

#include <cmath>
#include <sstream>

#include "core/error.h"

namespace sd {

double volume_multiplier(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, const Eigen::MatrixXd& c, double g) {
  if (v.size() == 0) return 0.0;
  const double cv = block_dot(c, v);
  if (!(cv > 0.0) || !std::isfinite(cv)) {
    std::ostringstream message;
    message << "volume constraint: c^T A^-1 c = " << cv
            << " is not positive (the volume gradient is orthogonal to the space of the step)";
    throw Error(message.str());
  }
  return (g - block_dot(c, u)) / cv;
}

std::function<bool(const BatchedPcg&)> combined_step_converged(const Eigen::MatrixXd& rhs, const Eigen::MatrixXd& c,
                                                               double g, double tolerance) {
  return [rhs, c, g, tolerance](const BatchedPcg& pcg) {
    const Eigen::MatrixXd& x = pcg.x();
    const double cv = block_dot(c, x.rightCols(3));
    if (!(cv > 0.0)) return false;
    const double dl = (g - block_dot(c, x.leftCols(3))) / cv;
    const Eigen::MatrixXd& R = pcg.residual();
    const Eigen::MatrixXd& Z = pcg.preconditioned();
    const Eigen::MatrixXd& F = pcg.first_direction();  // M^-1 rhs
    const double residual = block_dot(R.leftCols(3) + dl * R.rightCols(3), Z.leftCols(3) + dl * Z.rightCols(3));
    const double initial = block_dot(rhs.leftCols(3) + dl * rhs.rightCols(3), F.leftCols(3) + dl * F.rightCols(3));
    return residual <= tolerance * tolerance * initial;
  };
}

}  // namespace sd
