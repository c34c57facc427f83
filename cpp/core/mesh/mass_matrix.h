// Lumped (barycentric) mass matrix of a triangle mesh: M_ii = one third of the area of the triangles around
// vertex i. Diagonal and positive on a mesh without degenerate triangles, and sum_i M_ii is the surface area,
// so 1^T M f approximates the integral of f over the surface. With the cotangent Laplacian it gives the
// finite-element Laplace-Beltrami eigenproblem -L phi = lambda M phi (laplacian_eigenpairs.h).
#pragma once

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace sd {

// The diagonal of M, #V entries. Throws sd::Error when a vertex has no area around it (unreferenced, or
// only degenerate triangles): M would not be positive definite.
Eigen::VectorXd lumped_mass(const Vertices& V, const Faces& F);

}  // namespace sd
