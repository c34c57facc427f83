// Enclosed volume psi(X) = 1/6 sum over triangles (x_a x x_b) . x_c and its gradient (report eq. 10).
// Positive for a closed mesh with outward orientation.
#pragma once

#include "core/mesh.h"

namespace sd {

double signed_volume(const Vertices& V, const Faces& F);

// d psi / d x_i for every vertex: #V by 3 (row i is the gradient with respect to vertex i).
Vertices volume_gradient(const Vertices& V, const Faces& F);

}  // namespace sd
