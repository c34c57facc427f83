// Closest point on a solid triangle (interior, edges and corners) and the squared Euclidean distance to it, by
// the closest-point-on-triangle method of Ericson, "Real-Time Collision Detection" (2005), section 5.1.5.
// Degenerate triangles (collinear or coincident corners) are handled: the answer is then the closest point of
// the segment or point they collapse to.
#pragma once

#include "core/mesh/mesh.h"

namespace sd {

// Barycentric coordinates (u, v, w), u + v + w = 1, all >= 0, of the point of triangle abc closest to p:
// u a + v b + w c.
Eigen::Vector3d closest_point_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

double point_triangle_squared_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

}  // namespace sd
