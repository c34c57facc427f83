// Enclosed volume psi(X) = 1/6 sum over triangles ((x_a - o) x (x_b - o)) . (x_c - o) and its gradient
// (docs/method.md section 5). Positive for a closed mesh with outward orientation.
//
// The reference point o. For a closed surface the sum is the same about every point, but each triangle's term is
// of the size |x - o|^3 while their sum is of the size of the volume: summed about the origin, a model placed
// 1e3 diagonals away adds terms 1e9 times its volume and keeps few of its digits (a solve there stalled, and at
// 1e6 a valid mesh read as inward). So every sum takes o explicitly, near the model: volume_reference, near the
// centre of its bounding box. A solver fixes o at bind (from the rest mesh), so that the constraint is one function
// through a solve; a standalone measure takes the mesh's own (the two-argument signed_volume and volume_gradient).
//
// All three run on the thread pool (cpp/core/parallel) with results that do not depend on the thread
// count: the sums over triangles add per-block partial sums in block order, and the gradient gathers each
// vertex's triangles in increasing order, the order a serial loop over the triangles adds them in.
#pragma once

#include <array>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

using VolumeReference = Eigen::RowVector3d;

// Near the centre of the bounding box of the finite vertices that F's triangles use (indices valid; zero when there
// are none): the centre snapped to a grid as coarse as the box's diagonal, so that a model near the origin sums about
// the origin exactly as before. A vertex no triangle uses, however far, does not move it.
VolumeReference volume_reference(const Vertices& V, const Faces& F);

double signed_volume(const Vertices& V, const Faces& F, const VolumeReference& o);
// About the mesh's own volume_reference(V, F).
double signed_volume(const Vertices& V, const Faces& F);
// The same sum per label: entry k sums the triangles with label[f] == k (labels in [0, count)), with the blocks
// and their order of signed_volume, so that one label holding every triangle gives signed_volume to the bit.
Eigen::VectorXd signed_volumes(const Vertices& V, const Faces& F, const std::vector<int>& label, int count,
                               const VolumeReference& o);

// The triangles around each vertex: those of vertex v are triangle[start[v] .. start[v + 1]), increasing, and
// corner[s] is v's corner (0, 1, 2) in triangle[s] (a degenerate triangle listing v more than once comes that often
// in a row, once per corner; kept so that the gradients, made every iteration, need not look for it).
struct VertexTriangles {
  std::vector<int> start;
  std::vector<int> triangle;
  std::vector<int> corner;
};
VertexTriangles vertex_triangles(int vertex_count, const Faces& F);

// d psi / d x_i for every vertex: #V by 3 (row i is the gradient with respect to vertex i). The first form is
// about the mesh's own volume_reference; the second reuses the triangles around each vertex (a solver computes
// them once per mesh) and takes the solver's fixed o.
Vertices volume_gradient(const Vertices& V, const Faces& F);
Vertices volume_gradient(const Vertices& V, const Faces& F, const VertexTriangles& around, const VolumeReference& o);

// psi(V + t D) is a cubic in t: returns its coefficients {a0, a1, a2, a3}, psi(V + t D) = a0 + a1 t + a2 t^2 +
// a3 t^3 (so a0 = psi(V) and a1 = grad psi(V) . D), psi summed about o. One pass over the triangles; the volume
// restoration then solves for t without touching the mesh again.
std::array<double, 4> volume_along(const Vertices& V, const Vertices& D, const Faces& F, const VolumeReference& o);

}  // namespace sd
