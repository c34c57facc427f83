#include "core/mesh/mesh.h"

#include <limits>

namespace sd {

double bounding_box_diagonal(const Vertices& V) {
  if (V.rows() == 0) return 0.0;
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

Eigen::Matrix<double, Eigen::Dynamic, 6> group_boxes(const Vertices& V, const Faces& F,
                                                     const std::vector<int>& group_of_face, int count) {
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::Matrix<double, Eigen::Dynamic, 6> box(count, 6);
  box.leftCols(3).setConstant(inf);
  box.rightCols(3).setConstant(-inf);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int g = group_of_face[static_cast<size_t>(f)];
    // The checks call this on meshes not yet validated: a triangle with an index out of range has no corners.
    if (g < 0 || g >= count || (F.row(f).array() < 0).any() || (F.row(f).array() >= V.rows()).any()) continue;
    for (int corner = 0; corner < 3; ++corner) {
      box.row(g).head<3>() = box.row(g).head<3>().cwiseMin(V.row(F(f, corner)));
      box.row(g).tail<3>() = box.row(g).tail<3>().cwiseMax(V.row(F(f, corner)));
    }
  }
  return box;
}

}  // namespace sd
