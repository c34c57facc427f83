// 3D mean value coordinates (Ju, Schaefer and Warren 2005, the per-triangle formula with the on-face
// and in-plane special cases) of points with respect to a closed, outward triangle cage.
// Rows sum to 1 and W P0 = points (linear precision). Inside a concave cage weights may be negative.
#pragma once

#include <cstddef>
#include <functional>

#include "core/mesh.h"
#include "core/weight_matrix.h"

namespace sd {

struct MvcOptions {
  bool single_precision = false;
  // Refuse (sd::Error with advice) when W would need more bytes than this.
  std::size_t memory_budget_bytes = std::size_t(1) << 30;
  // Called now and then with the fraction done; return false to cancel (throws sd::Error "cancelled").
  std::function<bool(double)> progress;
};

// W (#points by #cage vertices). Throws sd::Error when a point is outside the cage (naming how many and
// the first few indices), when the budget is exceeded, or when cancelled.
WeightMatrix mean_value_coordinates(const Vertices& points, const Mesh& cage, const MvcOptions& options = {});

// One row of W for one point (the reference for tests and for points added later).
Eigen::RowVectorXd mean_value_coordinates_row(const Eigen::RowVector3d& point, const Mesh& cage);

}  // namespace sd
