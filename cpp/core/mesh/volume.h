// Enclosed volume psi(X) = 1/6 sum over triangles (x_a x x_b) . x_c and its gradient (docs/method.md section 5).
// Positive for a closed mesh with outward orientation.
#pragma once

#include <array>

#include "core/mesh/mesh.h"

namespace sd {

double signed_volume(const Vertices& V, const Faces& F);

// d psi / d x_i for every vertex: #V by 3 (row i is the gradient with respect to vertex i).
Vertices volume_gradient(const Vertices& V, const Faces& F);

// psi(V + t D) is a cubic in t: returns its coefficients {a0, a1, a2, a3}, psi(V + t D) = a0 + a1 t + a2 t^2 +
// a3 t^3 (so a0 = psi(V) and a1 = grad psi(V) . D). One pass over the triangles; the volume restoration
// then solves for t without touching the mesh again.
std::array<double, 4> volume_along(const Vertices& V, const Vertices& D, const Faces& F);

}  // namespace sd
