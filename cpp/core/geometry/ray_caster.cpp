#include "core/geometry/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sd {
namespace {

constexpr int kLeafSize = 4;

// The ray prepared for slab tests: 1 / direction per axis and which box corner it meets first.
struct PreparedRay {
  Eigen::Vector3d origin;
  double inv[3];
  int near_is_hi[3];  // 1 where the direction is negative: the ray enters through the box's upper side
};

// The entry parameter of the ray into the box, clipped to [t_min, t_max]; +inf when it misses the box.
inline double entry(const double lo[3], const double hi[3], const PreparedRay& ray, double t_min, double t_max) {
  double t0 = t_min, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    const double near = ((ray.near_is_hi[a] ? hi[a] : lo[a]) - ray.origin[a]) * ray.inv[a];
    const double far = ((ray.near_is_hi[a] ? lo[a] : hi[a]) - ray.origin[a]) * ray.inv[a];
    // NaN (0 * inf: the origin on a slab plane of a flat box) leaves the interval as it is.
    if (near > t0) t0 = near;
    if (far < t1) t1 = far;
  }
  return t0 <= t1 ? t0 : std::numeric_limits<double>::infinity();
}

}  // namespace

RayCaster::RayCaster(const Mesh& mesh) {
  const int faces = static_cast<int>(mesh.F.rows());
  faces_.resize(faces);
  order_.resize(faces);
  for (int f = 0; f < faces; ++f) {
    Face& face = faces_[f];
    face.p0 = mesh.V.row(mesh.F(f, 0)).transpose();
    const Eigen::Vector3d e1 = mesh.V.row(mesh.F(f, 1)).transpose() - face.p0;
    const Eigen::Vector3d e2 = mesh.V.row(mesh.F(f, 2)).transpose() - face.p0;
    face.normal = e1.cross(e2);
    const double area2 = face.normal.squaredNorm();
    // Degenerate triangles keep zero vectors: no ray hits them.
    face.dual1 = area2 > 0 ? Eigen::Vector3d(e2.cross(face.normal) / area2) : Eigen::Vector3d::Zero();
    face.dual2 = area2 > 0 ? Eigen::Vector3d(face.normal.cross(e1) / area2) : Eigen::Vector3d::Zero();
    order_[f] = f;
  }
  nodes_.reserve(2 * faces / kLeafSize + 2);
  if (faces > 0) build(0, faces, mesh);
}

int RayCaster::build(int begin, int end, const Mesh& mesh) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (int i = begin; i < end; ++i)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = mesh.V.row(mesh.F(order_[i], k)).transpose();
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  for (int a = 0; a < 3; ++a) {
    // Widened a little: a hit on the box's face must not be lost to rounding in the slab test.
    const double pad = 1e-9 * (hi[a] - lo[a]) + 1e-300;
    nodes_[id].lo[a] = lo[a] - pad;
    nodes_[id].hi[a] = hi[a] + pad;
  }
  if (end - begin <= kLeafSize) {
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    return id;
  }
  int axis;
  (hi - lo).maxCoeff(&axis);
  const int middle = (begin + end) / 2;
  auto centre = [&](int f) {
    return mesh.V(mesh.F(f, 0), axis) + mesh.V(mesh.F(f, 1), axis) + mesh.V(mesh.F(f, 2), axis);
  };
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](int a, int b) { return centre(a) < centre(b) || (centre(a) == centre(b) && a < b); });
  const int left = build(begin, middle, mesh);
  const int right = build(middle, end, mesh);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

bool RayCaster::intersect(int f, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min,
                          double t_max, RayHit& hit) const {
  const Face& face = faces_[f];
  const double along = face.normal.dot(direction);
  if (along == 0.0) return false;  // parallel to the plane, or a degenerate triangle
  const Eigen::Vector3d to_plane = face.p0 - origin;
  const double t = face.normal.dot(to_plane) / along;
  if (!(t > t_min && t < t_max)) return false;
  const Eigen::Vector3d y = t * direction - to_plane;  // the hit point - p0
  const double u = y.dot(face.dual1);
  if (u < 0.0 || u > 1.0) return false;
  const double v = y.dot(face.dual2);
  if (v < 0.0 || u + v > 1.0) return false;
  hit = RayHit{f, t, u, v};
  return true;
}

RayHit RayCaster::first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min, double t_max,
                            int skip) const {
  RayHit best;
  if (nodes_.empty()) return best;
  PreparedRay ray{origin, {}, {}};
  for (int a = 0; a < 3; ++a) {
    ray.inv[a] = 1.0 / direction[a];
    ray.near_is_hi[a] = direction[a] < 0;
  }
  double t_best = t_max;
  // Nodes wait on the stack with their entry parameter; one whose entry lies beyond the best hit found
  // since it was pushed is dropped without another test.
  struct Pending {
    int node;
    double entry;
  } stack[64];
  int top = 0;
  const double root = entry(nodes_[0].lo, nodes_[0].hi, ray, t_min, t_best);
  if (root == std::numeric_limits<double>::infinity()) return best;
  stack[top++] = {0, root};
  while (top > 0) {
    const Pending pending = stack[--top];
    if (pending.entry >= t_best) continue;
    const Node& node = nodes_[pending.node];
    if (node.left < 0) {
      for (int i = node.begin; i < node.end; ++i) {
        const int f = order_[i];
        if (f != skip && intersect(f, origin, direction, t_min, t_best, best)) t_best = best.t;
      }
      continue;
    }
    // The nearer child goes on top of the stack, so it is searched first and tightens t_best for the other.
    const double left = entry(nodes_[node.left].lo, nodes_[node.left].hi, ray, t_min, t_best);
    const double right = entry(nodes_[node.right].lo, nodes_[node.right].hi, ray, t_min, t_best);
    const bool left_first = left <= right;
    const Pending near{left_first ? node.left : node.right, left_first ? left : right};
    const Pending far{left_first ? node.right : node.left, left_first ? right : left};
    if (far.entry < t_best) stack[top++] = far;
    if (near.entry < t_best) stack[top++] = near;
  }
  return best;
}

void RayCaster::faces_in_region(const std::vector<HalfSpace>& region, std::vector<int>& out) const {
  if (nodes_.empty()) return;
  // A box lies wholly outside normal . y >= offset when even its corner farthest along the normal does.
  auto outside = [&](const Node& node) {
    for (const HalfSpace& h : region) {
      double reach = 0;
      for (int a = 0; a < 3; ++a) reach += h.normal[a] * (h.normal[a] > 0 ? node.hi[a] : node.lo[a]);
      if (reach < h.offset) return true;
    }
    return false;
  };
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (outside(node)) continue;
    if (node.left < 0) {
      for (int i = node.begin; i < node.end; ++i) out.push_back(order_[i]);
    } else {
      stack[top++] = node.right;
      stack[top++] = node.left;
    }
  }
}

}  // namespace sd
