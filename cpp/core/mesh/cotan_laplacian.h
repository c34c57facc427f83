// Cotangent Laplacian of a triangle mesh (docs/method.md section 3):
//   L_ij = (cot a_ij + cot b_ij) / 2 for each edge ij (a, b the angles opposite the edge),
//   L_ii = -sum_j L_ij.
// So L * 1 = 0, L is symmetric and negative semidefinite; no area normalisation. #V by #V, applied to
// x, y and z alike. Negative cotangents (obtuse angles) are kept as they are.
#pragma once

#include <Eigen/Sparse>

#include "core/mesh/mesh.h"

namespace sd {

Eigen::SparseMatrix<double> cotan_laplacian(const Vertices& V, const Faces& F);

}  // namespace sd
