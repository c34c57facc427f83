// Ray and region queries against a fixed triangle mesh (the positive mean value coordinates' visibility
// tests). A bounding volume hierarchy (median splits along the longest axis, up to 4 triangles per leaf)
// stored flat, children visited nearest first, and a ray-triangle test with each triangle's plane and dual
// edge vectors prepared once: the distance along the ray to the plane first, then the hit's barycentric
// coordinates by two dot products. Queries only read the structure, so any number of threads may query at
// once, and an answer depends on nothing but the query's arguments.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

struct RayHit {
  int face = -1;        // -1: no triangle hit within (t_min, t_max)
  double t = 0;         // origin + t direction is the hit point
  double u = 0, v = 0;  // barycentric coordinates of the hit: (1 - u - v) at corner 0, u at corner 1, v at corner 2
};

class RayCaster {
 public:
  RayCaster() = default;
  explicit RayCaster(const Mesh& mesh);

  // The hit with the smallest t in (t_min, t_max), ignoring triangle `skip` (-1: none). A ray through a shared
  // edge or vertex reports one of the triangles there. `direction` need not be unit length (t is in its units).
  RayHit first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min, double t_max,
                   int skip = -1) const;

  // Whether the ray meets triangle `face` at a t in (t_min, t_max); fills `hit` when it does.
  bool intersect(int face, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min, double t_max,
                 RayHit& hit) const;

  // A half-space normal . y >= offset.
  struct HalfSpace {
    Eigen::Vector3d normal;
    double offset;
  };
  // Appends to `out` (in the tree's order) every triangle of a leaf whose box meets the intersection of the
  // half-spaces (a superset of the triangles that meet it; callers test the triangles themselves).
  void faces_in_region(const std::vector<HalfSpace>& region, std::vector<int>& out) const;

  int size() const { return static_cast<int>(faces_.size()); }

 private:
  struct Node {
    double lo[3], hi[3];        // bounds
    int left = -1, right = -1;  // inner node: the children; -1 for a leaf
    int begin = 0, end = 0;     // leaf: faces order_[begin..end)
  };
  int build(int begin, int end, const Mesh& mesh);

  std::vector<Node> nodes_;
  std::vector<int> order_;
  struct Face {
    Eigen::Vector3d p0;      // corner 0
    Eigen::Vector3d normal;  // (p1 - p0) x (p2 - p0); zero for a degenerate triangle
    Eigen::Vector3d dual1;   // (y - p0) . dual1 = u for y = p0 + u (p1 - p0) + v (p2 - p0) in the plane
    Eigen::Vector3d dual2;   // (y - p0) . dual2 = v
  };
  std::vector<Face> faces_;
};

}  // namespace sd
