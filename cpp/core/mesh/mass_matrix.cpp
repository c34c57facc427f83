#include "core/mesh/mass_matrix.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace sd {

Eigen::VectorXd lumped_mass(const Vertices& V, const Faces& F) {
  const Eigen::Index n = V.rows();
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(n);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= n)
        throw Error(ErrorCode::InvalidMesh, "mass matrix: triangle " + std::to_string(f) + " has vertex index " +
                                                std::to_string(F(f, k)) + " outside [0, " + std::to_string(n) + ")");
    const Eigen::RowVector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const double third = (b - a).cross(c - a).norm() / 6.0;  // a third of the triangle's area
    for (int k = 0; k < 3; ++k) mass[F(f, k)] += third;
  }
  for (Eigen::Index i = 0; i < n; ++i)
    if (!(mass[i] > 0.0) || !std::isfinite(mass[i]))
      throw Error(ErrorCode::InvalidMesh, "mass matrix: vertex " + std::to_string(i) +
                                              " has no area around it (unreferenced, or only degenerate triangles)");
  return mass;
}

}  // namespace sd
