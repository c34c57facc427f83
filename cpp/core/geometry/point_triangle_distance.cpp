#include "core/geometry/point_triangle_distance.h"

#include <algorithm>

namespace sd {
namespace {

// Parameter t in [0, 1] of the point of segment ab closest to p.
double segment_parameter(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  return len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
}

// A (near-)degenerate triangle has no well-defined interior: the closest of the points on its three edges.
Eigen::Vector3d closest_on_edges(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c) {
  const double tab = segment_parameter(p, a, b), tbc = segment_parameter(p, b, c), tca = segment_parameter(p, c, a);
  const Eigen::Vector3d candidates[3] = {{1 - tab, tab, 0}, {0, 1 - tbc, tbc}, {tca, 0, 1 - tca}};
  Eigen::Vector3d best = candidates[0];
  double best_d2 = (best.x() * a + best.y() * b + best.z() * c - p).squaredNorm();
  for (int i = 1; i < 3; ++i) {
    const Eigen::Vector3d& w = candidates[i];
    const double d2 = (w.x() * a + w.y() * b + w.z() * c - p).squaredNorm();
    if (d2 < best_d2) best = w, best_d2 = d2;
  }
  return best;
}

}  // namespace

Eigen::Vector3d closest_point_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const Eigen::Vector3d n = ab.cross(ac);
  const double scale = std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()});
  if (!(n.squaredNorm() > 1e-24 * scale * scale)) return closest_on_edges(p, a, b, c);
  // Voronoi regions of the corners, then of the edges, else the face (Ericson 5.1.5).
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return {1 - t, t, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return {1 - t, 0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - t, t};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

double point_triangle_squared_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c) {
  const Eigen::Vector3d w = closest_point_barycentric(p, a, b, c);
  return (w.x() * a + w.y() * b + w.z() * c - p).squaredNorm();
}

}  // namespace sd
