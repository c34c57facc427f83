#include "core/geometry/aabb_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>

#include "core/geometry/point_triangle_distance.h"

namespace sd {

namespace {
constexpr int kLeafSize = 4;

}  // namespace

void AabbTree::build(std::vector<Box3> boxes) {
  boxes_ = std::move(boxes);
  order_.resize(boxes_.size());
  for (size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
  nodes_.clear();
  nodes_.reserve(2 * boxes_.size() / kLeafSize + 2);
  if (!boxes_.empty()) build_node(0, static_cast<int>(boxes_.size()));
}

int AabbTree::build_node(int begin, int end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Box3 box;
  for (int i = begin; i < end; ++i) box.extend(boxes_[order_[i]]);
  nodes_[id].box = box;
  if (end - begin <= kLeafSize) {
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    return id;
  }
  int axis;
  box.sizes().maxCoeff(&axis);
  const int middle = (begin + end) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](int a, int b) { return boxes_[a].center()[axis] < boxes_[b].center()[axis]; });
  const int left = build_node(begin, middle);
  const int right = build_node(middle, end);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

bool AabbTree::overlapping(const Box3& query, const std::function<bool(int)>& visit) const {
  if (nodes_.empty()) return true;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!node.box.intersects(query)) continue;
    if (node.left < 0) {
      for (int i = node.begin; i < node.end; ++i)
        if (boxes_[order_[i]].intersects(query) && !visit(order_[i])) return false;
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  return true;
}

double AabbTree::minimum(const std::function<double(const Box3&)>& lower_bound,
                         const std::function<double(int)>& distance) const {
  double best = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  using Entry = std::pair<double, int>;  // (bound, node), smallest bound first
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  queue.push({lower_bound(nodes_[0].box), 0});
  while (!queue.empty()) {
    auto [bound, id] = queue.top();
    queue.pop();
    if (bound >= best) break;
    const Node& node = nodes_[id];
    if (node.left < 0) {
      for (int i = node.begin; i < node.end; ++i) best = std::min(best, distance(order_[i]));
    } else {
      for (int child : {node.left, node.right}) {
        double b = lower_bound(nodes_[child].box);
        if (b < best) queue.push({b, child});
      }
    }
  }
  return best;
}

std::vector<Box3> triangle_boxes(const Vertices& V, const Faces& F, double margin) {
  std::vector<Box3> boxes(F.rows());
  for (int f = 0; f < F.rows(); ++f) {
    Box3 box;
    for (int k = 0; k < 3; ++k) box.extend(V.row(F(f, k)).transpose().eval());
    box.min().array() -= margin;
    box.max().array() += margin;
    boxes[f] = box;
  }
  return boxes;
}

double squared_distance_to_triangles(const AabbTree& tree, const Mesh& mesh, const Eigen::Vector3d& p) {
  return tree.minimum([&](const Box3& box) { return box.squaredExteriorDistance(p); },
                      [&](int f) {
                        return point_triangle_squared_distance(p, mesh.V.row(mesh.F(f, 0)).transpose(),
                                                               mesh.V.row(mesh.F(f, 1)).transpose(),
                                                               mesh.V.row(mesh.F(f, 2)).transpose());
                      });
}

}  // namespace sd
