// Exact-in-spirit, tolerance-aware intersection tests between triangles, and the self-intersection and
// surface-crossing queries built on them (AABB-tree broad phase, core/geometry/aabb_tree.h).
// Tolerance convention: `tol` is a length; points within `tol` of a triangle's plane count as on it and
// near-touching counts as intersecting, so a positive tol makes every test conservative (it reports
// more, never less). Used by cage generation to keep the cage free of self-intersections and off the mesh.
#pragma once

#include <utility>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

// Does the closed segment pq meet the closed triangle abc? Coplanar configurations are decided in 2D.
// Degenerate (zero-area) triangles never intersect anything here; callers reject them separately.
bool segment_intersects_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b, const Eigen::Vector3d& c, double tol);

// Do two closed triangles meet? (Two triangles meet iff an edge of one meets the other.)
bool triangles_intersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                         const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2, double tol);

// Do faces fa and fb of one mesh intersect anywhere other than along what they share? Faces sharing one
// vertex intersect iff an opposite edge meets the other face; faces sharing an edge intersect iff they are
// folded onto each other (normals opposite within `fold_cos`, e.g. -0.9999); identical faces always do.
bool faces_intersect(const Vertices& V, const Eigen::Vector3i& fa, const Eigen::Vector3i& fb, double tol,
                     double fold_cos = -0.9999);

// Pairs (f, g), f < g, of intersecting faces of one mesh; at most `max_pairs` are returned. `fold_cos` as
// for faces_intersect: the default also counts nearly folded edges (what cage generation must avoid);
// -1 + 1e-10 counts only faces folded flat onto each other.
std::vector<std::pair<int, int>> self_intersections(const Mesh& mesh, double tol, int max_pairs = 100,
                                                    double fold_cos = -0.9999);

// Pairs (face of a, face of b) of intersecting triangles of two different meshes; at most `max_pairs`.
std::vector<std::pair<int, int>> surface_crossings(const Mesh& a, const Mesh& b, double tol, int max_pairs = 100);

}  // namespace sd
