#include "core/geometry/self_intersection.h"

#include <algorithm>
#include <cmath>

#include "core/geometry/aabb_tree.h"

namespace sd {
namespace {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Distance-like orientation of r relative to the directed line uv (positive on the left), scaled to a length.
double side(const Vec2& u, const Vec2& v, const Vec2& r) {
  const double length = (v - u).norm();
  return length > 0 ? cross2(v - u, r - u) / length : (r - u).norm();
}

bool point_in_triangle_2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c, double tol) {
  // Orientation-independent: all sides of one sign (within tol).
  const double s0 = side(a, b, p), s1 = side(b, c, p), s2 = side(c, a, p);
  return (s0 >= -tol && s1 >= -tol && s2 >= -tol) || (s0 <= tol && s1 <= tol && s2 <= tol);
}

double point_segment_distance_2d(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

bool segments_intersect_2d(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b, double tol) {
  const double d1 = side(a, b, p), d2 = side(a, b, q), d3 = side(p, q, a), d4 = side(p, q, b);
  if (((d1 > tol && d2 < -tol) || (d1 < -tol && d2 > tol)) && ((d3 > tol && d4 < -tol) || (d3 < -tol && d4 > tol)))
    return true;
  // Touching or collinear: some endpoint lies within tol of the other segment.
  return point_segment_distance_2d(p, a, b) <= tol || point_segment_distance_2d(q, a, b) <= tol ||
         point_segment_distance_2d(a, p, q) <= tol || point_segment_distance_2d(b, p, q) <= tol;
}

// Drops the coordinate along the dominant axis of the normal.
Vec2 project(const Vec3& x, int drop) {
  return drop == 0 ? Vec2(x.y(), x.z()) : drop == 1 ? Vec2(x.z(), x.x()) : Vec2(x.x(), x.y());
}

Vec3 row(const Vertices& V, int i) { return V.row(i).transpose(); }

}  // namespace

bool segment_intersects_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c,
                                 double tol) {
  Vec3 n = (b - a).cross(c - a);
  const double area2 = n.norm();
  if (!(area2 > 0)) return false;
  n /= area2;
  const double dp = n.dot(p - a), dq = n.dot(q - a);
  if ((dp > tol && dq > tol) || (dp < -tol && dq < -tol)) return false;
  if (std::abs(dp) <= tol && std::abs(dq) <= tol) {
    int drop;
    n.cwiseAbs().maxCoeff(&drop);
    const Vec2 p2 = project(p, drop), q2 = project(q, drop);
    const Vec2 a2 = project(a, drop), b2 = project(b, drop), c2 = project(c, drop);
    return point_in_triangle_2d(p2, a2, b2, c2, tol) || point_in_triangle_2d(q2, a2, b2, c2, tol) ||
           segments_intersect_2d(p2, q2, a2, b2, tol) || segments_intersect_2d(p2, q2, b2, c2, tol) ||
           segments_intersect_2d(p2, q2, c2, a2, tol);
  }
  // The point of the segment closest to the plane (the crossing, or the near end when it only comes close).
  Vec3 x;
  if ((dp >= 0) != (dq >= 0)) {
    x = p + (dp / (dp - dq)) * (q - p);
  } else {
    x = std::abs(dp) < std::abs(dq) ? p : q;
    x -= n * n.dot(x - a);
  }
  const Vec3* corners[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const Vec3& u = *corners[k];
    const Vec3& v = *corners[(k + 1) % 3];
    const double length = (v - u).norm();
    if (n.dot((v - u).cross(x - u)) < -tol * length) return false;
  }
  return true;
}

namespace {
// True when all three points are more than tol from the plane of abc, on the same side (a quick rejection).
bool beyond_plane(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                  double tol) {
  Vec3 n = (b - a).cross(c - a);
  const double length = n.norm();
  if (!(length > 0)) return false;
  n /= length;
  const double d0 = n.dot(p0 - a), d1 = n.dot(p1 - a), d2 = n.dot(p2 - a);
  return (d0 > tol && d1 > tol && d2 > tol) || (d0 < -tol && d1 < -tol && d2 < -tol);
}
}  // namespace

bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2,
                         double tol) {
  if (beyond_plane(a0, a1, a2, b0, b1, b2, tol) || beyond_plane(b0, b1, b2, a0, a1, a2, tol)) return false;
  return segment_intersects_triangle(a0, a1, b0, b1, b2, tol) || segment_intersects_triangle(a1, a2, b0, b1, b2, tol) ||
         segment_intersects_triangle(a2, a0, b0, b1, b2, tol) || segment_intersects_triangle(b0, b1, a0, a1, a2, tol) ||
         segment_intersects_triangle(b1, b2, a0, a1, a2, tol) || segment_intersects_triangle(b2, b0, a0, a1, a2, tol);
}

bool faces_intersect(const Vertices& V, const Eigen::Vector3i& fa, const Eigen::Vector3i& fb, double tol,
                     double fold_cos) {
  int shared = 0, ia = -1, ib = -1;  // for one shared vertex: its slot in fa and in fb
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (fa[i] == fb[j]) {
        ++shared;
        ia = i;
        ib = j;
      }
  const Vec3 a0 = row(V, fa[0]), a1 = row(V, fa[1]), a2 = row(V, fa[2]);
  const Vec3 b0 = row(V, fb[0]), b1 = row(V, fb[1]), b2 = row(V, fb[2]);
  if (shared == 0) return triangles_intersect(a0, a1, a2, b0, b1, b2, tol);
  if (shared == 3) return true;
  if (shared == 2) {
    const Vec3 na = (a1 - a0).cross(a2 - a0).normalized(), nb = (b1 - b0).cross(b2 - b0).normalized();
    return na.dot(nb) < fold_cos;
  }
  const Vec3 pa = row(V, fa[(ia + 1) % 3]), qa = row(V, fa[(ia + 2) % 3]);
  const Vec3 pb = row(V, fb[(ib + 1) % 3]), qb = row(V, fb[(ib + 2) % 3]);
  return segment_intersects_triangle(pa, qa, b0, b1, b2, tol) || segment_intersects_triangle(pb, qb, a0, a1, a2, tol);
}

std::vector<std::pair<int, int>> self_intersections(const Mesh& mesh, double tol, int max_pairs, double fold_cos) {
  std::vector<std::pair<int, int>> pairs;
  const AabbTree tree(triangle_boxes(mesh.V, mesh.F, tol));
  for (int f = 0; f < mesh.F.rows() && static_cast<int>(pairs.size()) < max_pairs; ++f) {
    const Eigen::Vector3i fa = mesh.F.row(f).transpose();
    tree.overlapping(tree.box(f), [&](int g) {
      if (g <= f) return true;
      if (faces_intersect(mesh.V, fa, mesh.F.row(g).transpose(), tol, fold_cos)) pairs.push_back({f, g});
      return static_cast<int>(pairs.size()) < max_pairs;
    });
  }
  return pairs;
}

std::vector<std::pair<int, int>> surface_crossings(const Mesh& a, const Mesh& b, double tol, int max_pairs) {
  std::vector<std::pair<int, int>> pairs;
  const AabbTree tree(triangle_boxes(b.V, b.F, tol));
  const std::vector<Box3> boxes_a = triangle_boxes(a.V, a.F, tol);
  for (int f = 0; f < a.F.rows() && static_cast<int>(pairs.size()) < max_pairs; ++f) {
    const Vec3 a0 = row(a.V, a.F(f, 0)), a1 = row(a.V, a.F(f, 1)), a2 = row(a.V, a.F(f, 2));
    tree.overlapping(boxes_a[f], [&](int g) {
      if (triangles_intersect(a0, a1, a2, row(b.V, b.F(g, 0)), row(b.V, b.F(g, 1)), row(b.V, b.F(g, 2)), tol))
        pairs.push_back({f, g});
      return static_cast<int>(pairs.size()) < max_pairs;
    });
  }
  return pairs;
}

}  // namespace sd
