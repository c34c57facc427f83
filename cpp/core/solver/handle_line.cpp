#include "core/solver/handle_line.h"

#include <string>

#include "core/error.h"

namespace sd {

Eigen::RowVector3d line_direction(const HandleLine& line, const Eigen::RowVector3d& target) {
  Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
  if (line.kind == HandleLine::Kind::Along) d = line.vector.transpose();
  if (line.kind == HandleLine::Kind::From) d = target - line.vector.transpose();
  const double length = d.norm();
  return length > 0.0 ? Eigen::RowVector3d(d / length) : Eigen::RowVector3d::Zero();
}

void validate_handle_line(const HandleLine& line, const char* where) {
  if (line.kind == HandleLine::Kind::None) return;
  const char* name = line.kind == HandleLine::Kind::Along ? "along" : "from";
  if (!line.vector.allFinite()) throw Error(std::string(where) + ": \"" + name + "\" must be 3 finite numbers");
  if (line.kind == HandleLine::Kind::Along && !(line.vector.norm() > 0.0))
    throw Error(std::string(where) + ": \"along\" must be a nonzero direction");
}

}  // namespace sd
