// Progressive hull decimation (Sander, Gu, Gortler, Hoppe, Snyder 2000, "Silhouette clipping", section 3):
// edge collapses that only ever grow the enclosed region, so every coarser mesh encloses the finer one.
// For the collapse of edge (a, b) the new vertex v solves the 3-variable linear program
//     minimize   added volume  =  v . sum over the new fan (x_i x x_{i+1}) / 6  - old volume of the star
//     subject to n_f . v >= n_f . p_f   for every face f around a or b (v on the outer side of its plane)
// inside a box around the edge (Seidel-style incremental LP). Collapses are taken cheapest first (added
// volume plus a small edge-length term so flat regions coarsen evenly), and a collapse is refused when
//   - it would break manifoldness (link condition; valences >= 3),
//   - a new face is degenerate, flips, or folds onto a neighbour,
//   - a new face intersects another face of the hull (AABB tree + triangle tests, core/geometry/self_intersection.h),
//   - a new face comes within `clearance` of the obstacle surface (the mesh the hull must enclose).
// So the hull stays closed, manifold, free of self-intersections and off the obstacle at every step.
// Costs of edges near a collapse are re-planned lazily when they reach the top of the queue; when the
// queue runs dry above the target, one more round runs with the flip/fold quality checks relaxed.
#pragma once

#include <functional>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

struct ProgressiveHullOptions {
  int target_vertices = 100;
  const Mesh* obstacle = nullptr;  // surface the hull must never touch (may be null)
  double clearance = 0.0;          // minimum gap kept to the obstacle (a length, >= 0)
  double tolerance = 0.0;          // length tolerance of the self-intersection tests (>= 0)
  // Called now and then with the fraction done; return false to cancel (throws sd::Error "cancelled").
  std::function<bool(double)> progress;
};

struct ProgressiveHullStats {
  int collapses = 0;
  int refused = 0;  // collapses popped from the queue and refused by a check
};

// `start` must be closed, manifold and outward. Returns the decimated hull with unused vertices removed;
// it has target_vertices vertices unless every remaining collapse is refused (then more).
Mesh progressive_hull(const Mesh& start, const ProgressiveHullOptions& options, ProgressiveHullStats* stats = nullptr);

// The linear program above in normalized form: minimize c . x subject to n_i . x >= d_i (n_i unit) and
// |x_k| <= 1. Returns false when infeasible. Exposed for tests.
bool solve_lp3(const std::vector<Eigen::Vector3d>& normals, const std::vector<double>& offsets,
               const Eigen::Vector3d& c, Eigen::Vector3d& x);

}  // namespace sd
