// The projection constraint of Huang et al. 2006 (docs/method.md section 5.2): a handle seen through a view is
// held only across it. Each of its vertices must reach the line through its target along the view direction, and
// its depth along that line is left to the energy (a drag in the screen plane without choosing the depth).
//
//   Along: an orthographic view; every vertex's line runs along `vector` (any length, not zero).
//   From:  a perspective view from the eye at `vector`; a vertex's line runs through the eye and its target.
//   None:  a point target (the vertex must reach the target itself).
//
// In the energy the handle row w (x - t) becomes w (x - t) Q with Q = I - u u^T (u the line's unit direction):
// still least squares, two independent rows instead of three.
#pragma once

#include <Eigen/Core>

namespace sd {

struct HandleLine {
  enum class Kind { None, Along, From };
  Kind kind = Kind::None;
  Eigen::Vector3d vector = Eigen::Vector3d::Zero();  // Along: the direction; From: the eye

  static HandleLine along(const Eigen::Vector3d& direction) { return {Kind::Along, direction}; }
  static HandleLine from(const Eigen::Vector3d& eye) { return {Kind::From, eye}; }
  bool operator==(const HandleLine& o) const { return kind == o.kind && vector == o.vector; }
};

// The unit direction of the line through `target` (zero for Kind::None, and for an eye at the target itself,
// where no line is defined: the target is then a point target).
Eigen::RowVector3d line_direction(const HandleLine& line, const Eigen::RowVector3d& target);

// Whether any line's unit direction (rows of `current`) turned by more than kPreconditionerTurnDegrees from the
// one a preconditioner was factored with (rows of `factored`; a different row count counts as turned). An eye's
// lines turn with the targets during a drag; a preconditioner with stale directions costs products (on the
// built-in bar 3.3 per frame instead of 1.2), so it is remade past this angle.
constexpr double kPreconditionerTurnDegrees = 2.0;
bool lines_turned(const Eigen::MatrixXd& factored, const Eigen::MatrixXd& current);

// Throws sd::Error naming `where` when the line is not usable: a non-finite vector, or a zero direction.
void validate_handle_line(const HandleLine& line, const char* where);

}  // namespace sd
