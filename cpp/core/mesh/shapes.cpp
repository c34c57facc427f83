#include "core/mesh/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include "core/error.h"

namespace sd {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Accumulates vertices and triangles, welding vertices that land on the same point (box faces share
// their border vertices).
class MeshBuilder {
 public:
  int vertex(double x, double y, double z) {
    auto key = std::make_tuple(std::llround(x * 1e9), std::llround(y * 1e9), std::llround(z * 1e9));
    auto found = index_.find(key);
    if (found != index_.end()) return found->second;
    int id = static_cast<int>(points_.size());
    points_.push_back({x, y, z});
    index_.emplace(key, id);
    return id;
  }
  void triangle(int a, int b, int c) { triangles_.push_back({a, b, c}); }
  Mesh build() const {
    Mesh mesh;
    mesh.V.resize(static_cast<int>(points_.size()), 3);
    for (size_t i = 0; i < points_.size(); ++i)
      mesh.V.row(static_cast<int>(i)) << points_[i][0], points_[i][1], points_[i][2];
    mesh.F.resize(static_cast<int>(triangles_.size()), 3);
    for (size_t i = 0; i < triangles_.size(); ++i)
      mesh.F.row(static_cast<int>(i)) << triangles_[i][0], triangles_[i][1], triangles_[i][2];
    return mesh;
  }

 private:
  std::map<std::tuple<long long, long long, long long>, int> index_;
  std::vector<std::array<double, 3>> points_;
  std::vector<std::array<int, 3>> triangles_;
};

// One face of a box: origin corner + two edge vectors u, v with u x v pointing outward.
void add_grid_face(MeshBuilder& builder, const Eigen::Vector3d& origin, const Eigen::Vector3d& u,
                   const Eigen::Vector3d& v, int nu, int nv) {
  std::vector<int> ids((nu + 1) * (nv + 1));
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      Eigen::Vector3d p = origin + u * (double(i) / nu) + v * (double(j) / nv);
      ids[j * (nu + 1) + i] = builder.vertex(p.x(), p.y(), p.z());
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      int a = ids[j * (nu + 1) + i], b = ids[j * (nu + 1) + i + 1];
      int c = ids[(j + 1) * (nu + 1) + i + 1], d = ids[(j + 1) * (nu + 1) + i];
      builder.triangle(a, b, c);
      builder.triangle(a, c, d);
    }
}

// Six outward faces of the box [lo, hi] with (nx, ny, nz) subdivisions along each axis.
Mesh grid_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny, int nz) {
  if (nx < 1 || ny < 1 || nz < 1) throw Error("box subdivisions must be at least 1");
  MeshBuilder b;
  Eigen::Vector3d d = hi - lo;
  Eigen::Vector3d ex(d.x(), 0, 0), ey(0, d.y(), 0), ez(0, 0, d.z());
  add_grid_face(b, lo, ey, ex, ny, nx);       // z = lo (normal -z)
  add_grid_face(b, lo + ez, ex, ey, nx, ny);  // z = hi (normal +z)
  add_grid_face(b, lo, ex, ez, nx, nz);       // y = lo (normal -y)
  add_grid_face(b, lo + ey, ez, ex, nz, nx);  // y = hi (normal +y)
  add_grid_face(b, lo, ez, ey, nz, ny);       // x = lo (normal -x)
  add_grid_face(b, lo + ex, ey, ez, ny, nz);  // x = hi (normal +x)
  return b.build();
}

}  // namespace

Mesh make_box(double sx, double sy, double sz, int subdivisions) {
  Eigen::Vector3d half(sx / 2, sy / 2, sz / 2);
  return grid_box(-half, half, subdivisions, subdivisions, subdivisions);
}

Mesh make_bar_cage(double x0, double x1, double hy, double hz, int segments) {
  return grid_box(Eigen::Vector3d(x0, -hy, -hz), Eigen::Vector3d(x1, hy, hz), segments, 1, 1);
}

Mesh make_icosphere(int subdivisions, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> points = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                           {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                           {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                           {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : points) p.normalize();
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> midpoints;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto found = midpoints.find(key);
      if (found != midpoints.end()) return found->second;
      points.push_back((points[a] + points[b]).normalized());
      int id = static_cast<int>(points.size()) - 1;
      midpoints.emplace(key, id);
      return id;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& f : faces) {
      int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    faces.swap(finer);
  }
  Mesh mesh;
  mesh.V.resize(static_cast<int>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) mesh.V.row(static_cast<int>(i)) = radius * points[i].transpose();
  mesh.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) mesh.F.row(static_cast<int>(i)) << faces[i][0], faces[i][1], faces[i][2];
  return mesh;
}

Mesh make_capsule(double length, double radius, int rings, int cylinder_rings, int segments) {
  if (rings < 2 || cylinder_rings < 1 || segments < 3) throw Error("capsule resolution too low");
  // Profile from the -x pole to the +x pole: (x, r) pairs; the poles are separate vertices.
  std::vector<std::pair<double, double>> profile;
  for (int k = 1; k <= rings; ++k) {  // left hemisphere, pole excluded
    double phi = kPi / 2 * double(k) / rings;
    profile.push_back({-length / 2 - radius * std::cos(phi), radius * std::sin(phi)});
  }
  for (int k = 1; k < cylinder_rings; ++k)
    profile.push_back({-length / 2 + length * double(k) / cylinder_rings, radius});
  for (int k = rings; k >= 1; --k) {  // right hemisphere
    double phi = kPi / 2 * double(k) / rings;
    profile.push_back({length / 2 + radius * std::cos(phi), radius * std::sin(phi)});
  }
  const int ring_count = static_cast<int>(profile.size());
  Mesh mesh;
  mesh.V.resize(2 + ring_count * segments, 3);
  mesh.V.row(0) << -length / 2 - radius, 0, 0;
  for (int r = 0; r < ring_count; ++r)
    for (int s = 0; s < segments; ++s) {
      double theta = 2 * kPi * s / segments;
      mesh.V.row(1 + r * segments + s) << profile[r].first, profile[r].second * std::cos(theta),
          profile[r].second * std::sin(theta);
    }
  const int last = 1 + ring_count * segments;
  mesh.V.row(last) << length / 2 + radius, 0, 0;
  auto id = [&](int r, int s) { return 1 + r * segments + (s % segments); };
  std::vector<std::array<int, 3>> faces;
  for (int s = 0; s < segments; ++s) faces.push_back({0, id(0, s + 1), id(0, s)});
  for (int r = 0; r + 1 < ring_count; ++r)
    for (int s = 0; s < segments; ++s) {
      faces.push_back({id(r, s), id(r, s + 1), id(r + 1, s + 1)});
      faces.push_back({id(r, s), id(r + 1, s + 1), id(r + 1, s)});
    }
  for (int s = 0; s < segments; ++s) faces.push_back({last, id(ring_count - 1, s), id(ring_count - 1, s + 1)});
  mesh.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) mesh.F.row(static_cast<int>(i)) << faces[i][0], faces[i][1], faces[i][2];
  return mesh;
}

Mesh make_torus(double major_radius, double minor_radius, int rings, int segments) {
  if (rings < 3 || segments < 3) throw Error("torus resolution too low");
  if (!(minor_radius > 0.0) || !(major_radius > minor_radius))
    throw Error("torus: need 0 < minor radius < major radius");
  Mesh mesh;
  mesh.V.resize(rings * segments, 3);
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double u = 2 * kPi * r / rings, v = 2 * kPi * s / segments;
      const double radius = major_radius + minor_radius * std::cos(v);
      mesh.V.row(r * segments + s) << radius * std::cos(u), radius * std::sin(u), minor_radius * std::sin(v);
    }
  auto id = [&](int r, int s) { return (r % rings) * segments + (s % segments); };
  mesh.F.resize(2 * rings * segments, 3);
  int f = 0;
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {  // outward: (d/du) x (d/dv) points away from the tube's centre line
      mesh.F.row(f++) << id(r, s), id(r + 1, s), id(r + 1, s + 1);
      mesh.F.row(f++) << id(r, s), id(r + 1, s + 1), id(r, s + 1);
    }
  return mesh;
}

Vertices bend_along_x(const Vertices& V, double radius) {
  Vertices bent(V.rows(), 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const double angle = V(i, 0) / radius, r = radius - V(i, 1);
    bent.row(i) << r * std::sin(angle), radius - r * std::cos(angle), V(i, 2);
  }
  return bent;
}

}  // namespace sd
