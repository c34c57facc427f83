// The per-point kernel of mean value coordinates, shared by the mean value (mean_value_coordinates.h) and
// the positive mean value coordinates (positive_mean_value_coordinates.h): for a point x and a closed,
// outward triangle cage, the integrals
//   I_j(x) = integral over the unit sphere around x of  sum over the cage crossings y of the ray
//            +-phi_j(y) / |y - x|
// (phi_j the piecewise linear hat function of cage vertex j on the cage; + where the ray leaves the cage
// through a triangle, - where it enters), computed per triangle in closed form (Ju, Schaefer and Warren 2005,
// section 3.3, with the special cases of docs/mvc.md). Mean value coordinates are I / sum(I); the positive
// ones keep only the first crossing of each ray. A triangle is *front-facing* when x is on its inner side
// (det[u0 u1 u2] > 0): rays from an interior point leave the cage through front-facing triangles and enter
// it through the others, so the first crossing is always on a front-facing triangle.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

// Cage connectivity prepared once: vertex coordinates split by axis, unique edges, and for each triangle
// its vertices and the edges opposite them (edge k of a triangle joins vertices k+1 and k+2), so the arc
// of each edge (an arcsine) is computed once per point rather than once per adjacent triangle.
struct CageData {
  int m = 0;
  std::vector<double> px, py, pz;
  std::vector<int> edge_a, edge_b;
  std::vector<int> tri;       // 3 per triangle
  std::vector<int> tri_edge;  // 3 per triangle, tri_edge[3t+k] opposite tri[3t+k]
  double scale = 1.0;         // the cage's bounding-box diagonal
  int faces() const { return static_cast<int>(tri.size() / 3); }
};

// Throws sd::Error (InvalidMesh, the message starting with `what`) for fewer than 4 vertices or
// triangles, non-finite coordinates or out-of-range indices.
CageData prepare_cage(const Mesh& cage, const std::string& what);

enum class PointKind { Regular, OnVertex, OnFace };

// Evaluates one point; reuses its scratch arrays between points (no allocation per point). One per thread.
class MeanValueIntegrals {
 public:
  explicit MeanValueIntegrals(const CageData& cage);

  // Writes row[j] = I_j(x) (length m) and returns sum_j I_j(x), which is positive inside the cage and
  // negative outside (each ray contributes +1/r1 - 1/r2 + 1/r3 ... > 0 when it starts inside, < 0 when
  // outside). With `back_faces` given, only front-facing triangles are accumulated into row (the positive
  // coordinates' first crossings, before occlusion) and the others are listed there, while the return value
  // still sums over all triangles (the same inside test). A point on a cage vertex or triangle gets its delta
  // or barycentric row (summing to 1) and the kind says so; the return value is then 1.
  double integrate(double x, double y, double z, double* row, PointKind& kind, std::vector<int>* back_faces = nullptr);

  // |p_j - x| and (p_j - x) / |p_j - x| of the last point integrated.
  double distance(int j) const { return d_[j]; }
  Eigen::Vector3d direction(int j) const { return Eigen::Vector3d(ux_[j], uy_[j], uz_[j]); }

 private:
  void thin_triangle_weights(int t, double x, double y, double z);

  const CageData& c_;
  std::vector<double> ux_, uy_, uz_, d_, acc_;
  std::vector<double> theta_, cos_, sin_;
};

}  // namespace sd
