#include "core/aabb_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>

namespace sd {

namespace {
constexpr int kLeafSize = 4;

// Squared distance from p to triangle abc (closest point by regions, Ericson 2005, 5.1.5).
double point_triangle_distance2(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (a + ab * (d1 / (d1 - d3)) - p).squaredNorm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (a + ac * (d2 / (d2 - d6)) - p).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))) - p).squaredNorm();
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) return std::min({ap.squaredNorm(), bp.squaredNorm(), cp.squaredNorm()});
  return (a + ab * (vb / denom) + ac * (vc / denom) - p).squaredNorm();
}

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
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end, [&](int a, int b) {
    return boxes_[a].center()[axis] < boxes_[b].center()[axis];
  });
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
                        return point_triangle_distance2(p, mesh.V.row(mesh.F(f, 0)).transpose(),
                                                        mesh.V.row(mesh.F(f, 1)).transpose(),
                                                        mesh.V.row(mesh.F(f, 2)).transpose());
                      });
}

}  // namespace sd
