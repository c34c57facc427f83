// Static axis-aligned bounding-box tree over a list of boxes (triangles, usually): the broad phase of the
// intersection and distance queries used by cage generation and its validation. Built once by median
// splits along the longest axis; queries visit only the subtrees whose box overlaps the query.
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

using Box3 = Eigen::AlignedBox3d;

class AabbTree {
 public:
  AabbTree() = default;
  explicit AabbTree(std::vector<Box3> boxes) { build(std::move(boxes)); }
  void build(std::vector<Box3> boxes);

  int size() const { return static_cast<int>(boxes_.size()); }
  const Box3& box(int item) const { return boxes_[item]; }

  // Calls visit(item) for every item whose box overlaps `query` (closed boxes); stops early when visit
  // returns false. Returns false when it stopped early.
  bool overlapping(const Box3& query, const std::function<bool(int)>& visit) const;

  // Branch and bound: smallest value of distance(item) over the items, where lower_bound(box) never
  // exceeds distance(item) for an item inside `box`. Returns +inf for an empty tree.
  double minimum(const std::function<double(const Box3&)>& lower_bound,
                 const std::function<double(int)>& distance) const;

 private:
  struct Node {
    Box3 box;
    int left = -1, right = -1;  // children, or -1 for a leaf
    int begin = 0, end = 0;     // leaf: items order_[begin..end)
  };
  int build_node(int begin, int end);

  std::vector<Box3> boxes_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

// Bounding box of each triangle of (V, F), grown by `margin` on every side.
std::vector<Box3> triangle_boxes(const Vertices& V, const Faces& F, double margin = 0.0);

// Squared distance from p to the nearest triangle of `mesh`, given `tree` = AabbTree(triangle_boxes(mesh.V,
// mesh.F)). Closest point on a triangle by regions (Ericson 2005, "Real-Time Collision Detection" 5.1.5).
double squared_distance_to_triangles(const AabbTree& tree, const Mesh& mesh, const Eigen::Vector3d& p);

}  // namespace sd
