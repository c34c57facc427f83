#include "core/mesh/mesh.h"

namespace sd {

double bounding_box_diagonal(const Vertices& V) {
  if (V.rows() == 0) return 0.0;
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

}  // namespace sd
