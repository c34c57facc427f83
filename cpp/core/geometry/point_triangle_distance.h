// Squared Euclidean distance from a point to a solid triangle (interior, edges and corners), by the
// closest-point-on-triangle method of Ericson, "Real-Time Collision Detection" (2005), section 5.1.5.
// Degenerate triangles (collinear or coincident corners) are handled: the answer is then the distance
// to the segment or point they collapse to.
#pragma once

#include "core/mesh/mesh.h"

namespace sd {

double point_triangle_squared_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

}  // namespace sd
