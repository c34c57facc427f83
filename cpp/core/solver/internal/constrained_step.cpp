#include "core/solver/internal/constrained_step.h"

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
    throw Error(ErrorCode::NumericalFailure, message.str());
  }
  return (g - block_dot(c, u)) / cv;
}

}  // namespace sd
