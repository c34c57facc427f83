// 3D mean value coordinates (Ju, Schaefer and Warren 2005, "Mean value coordinates for closed triangular
// meshes", the per-triangle formula of their section 3.3 with the on-face and in-plane special cases) of
// points with respect to a closed, outward triangle cage.
//   W is #points by #cage vertices; rows sum to 1 and W P0 = points (linear precision). Inside a concave cage
//   weights may be negative (MvcReport::min_weight says how negative).
//   Computed in double; stored in float64 or float32 (MvcOptions::single_precision; see docs/mvc.md for the
//   accuracy effect: rows then sum to 1 within ~1e-7 and linear precision holds to ~1e-7 of the cage size).
//   Robust cases: a point on a cage vertex gets that vertex's delta row; a point on a cage triangle (or edge)
//   gets the triangle's barycentric coordinates; a triangle whose plane contains the point (point outside it)
//   contributes nothing, as do degenerate (zero-area) cage triangles.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>

#include "core/mesh/mesh.h"
#include "core/basis/basis_matrix.h"

namespace sd {

// The largest single allocation this build can make: in wasm the heap grows to 4 GB, but Emscripten's allocator
// (dlmalloc) takes from it through sbrk in increments below 2^31 bytes (less its own padding), so one W of 2.18 GB
// failed at once where 2.10 GB was bound. Natively, what size_t holds.
#ifdef __EMSCRIPTEN__
constexpr std::size_t kMaxAllocationBytes = (std::size_t(1) << 31) - (std::size_t(1) << 20);
#else
constexpr std::size_t kMaxAllocationBytes = std::numeric_limits<std::size_t>::max();
#endif

struct MvcOptions {
  bool single_precision = false;
  // Refuse (sd::Error with advice) when W would need more bytes than this.
  std::size_t memory_budget_bytes = std::size_t(1) << 30;
  // Called every few hundred rows with the fraction done (0..1) and once with 1 at the end; return false
  // (also at the end) to cancel (throws sd::Error "binding cancelled").
  std::function<bool(double)> progress;
};

// What the binding found, for diagnostics and the CLI.
struct MvcReport {
  double min_weight = 0.0;  // smallest entry of W (computed in double, before any float32 rounding)
  int min_weight_row = -1;  // where it is
  int min_weight_col = -1;
  int on_vertex = 0;       // points that coincide with a cage vertex (delta rows)
  int on_face = 0;         // points on a cage triangle or edge (barycentric rows)
  double evaluations = 0;  // point-triangle evaluations: #points x #cage triangles
  double seconds = 0;      // wall time of the binding
};

// W (#points by #cage vertices). Throws sd::Error when a point is outside the cage (naming how many and
// the first few indices), when the budget is exceeded, when the cage has out-of-range indices or when
// cancelled. `report`, when given, receives the minimum weight and counts.
BasisMatrix mean_value_coordinates(const Vertices& points, const Mesh& cage, const MvcOptions& options = {},
                                   MvcReport* report = nullptr);

// Throws the budget error of mean_value_coordinates when W for n points and m cage vertices would exceed
// options.memory_budget_bytes; callers with slow checks to run first (a mesh + cage validation) ask here.
void check_weights_budget(int n, int m, const MvcOptions& options);

// One row of W for one point (for points added later). Throws sd::Error when the point is outside.
Eigen::RowVectorXd mean_value_coordinates_row(const Eigen::RowVector3d& point, const Mesh& cage);

}  // namespace sd
