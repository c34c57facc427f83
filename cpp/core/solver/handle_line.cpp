#include "core/solver/handle_line.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace sd {

Eigen::RowVector3d line_direction(const HandleLine& line, const Eigen::RowVector3d& target) {
  Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
  if (line.kind == HandleLine::Kind::Along) d = line.vector.transpose();
  if (line.kind == HandleLine::Kind::From) d = target - line.vector.transpose();
  // Scaled by its largest entry first: the norm of [0, 0, 1e155] overflows and that of [0, 0, 1e-200] underflows,
  // and either made the line vanish (a point target) or ruined its direction.
  const double scale = d.cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || !std::isfinite(scale)) return Eigen::RowVector3d::Zero();
  return (d / scale).normalized();
}

bool lines_turned(const Eigen::MatrixXd& factored, const Eigen::MatrixXd& current) {
  if (factored.rows() != current.rows()) return true;
  const double cos_limit = std::cos(kPreconditionerTurnDegrees * 3.14159265358979323846 / 180.0);
  for (Eigen::Index k = 0; k < current.rows(); ++k) {
    const double a = factored.row(k).norm(), b = current.row(k).norm();
    if ((a == 0.0) != (b == 0.0)) return true;  // a line appeared or vanished (an eye reached its target)
    if (a > 0.0 && factored.row(k).dot(current.row(k)) < cos_limit * a * b) return true;
  }
  return false;
}

void validate_handle_line(const HandleLine& line, const char* where) {
  if (line.kind == HandleLine::Kind::None) return;
  const char* name = line.kind == HandleLine::Kind::Along ? "along" : "from";
  if (!line.vector.allFinite()) throw Error(std::string(where) + ": \"" + name + "\" must be 3 finite numbers");
  if (line.kind == HandleLine::Kind::Along && !(line.vector.cwiseAbs().maxCoeff() > 0.0))
    throw Error(std::string(where) + ": \"along\" must be a nonzero direction");
}

}  // namespace sd
