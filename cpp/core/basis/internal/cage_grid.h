// A regular grid over a closed cage for the harmonic coordinates (harmonic_coordinates.h): which grid nodes lie
// inside the cage, and where the grid lines cross the cage's triangles.
//   Nodes: origin + h (i, j, k), 0 <= i < n[0] etc.; the grid covers the cage's bounding box with a cell of
//   margin, and its origin is shifted by fixed fractions of h so that an axis-aligned cage face at a round
//   coordinate does not pass through a row of nodes.
//   Crossings: for each axis and each grid line along it, the points where the line meets a cage triangle,
//   sorted along the line, with the triangle and the point's barycentric coordinates in it. A line through a
//   triangle's edge or vertex is decided by simulation of simplicity (Edelsbrunner and Mucke 1990: the line is
//   moved by an infinitesimal (eps, eps^2) in its cross-section), so every line meets the closed cage an even
//   number of times and each crossing is counted once.
//   Inside: a node is inside when an odd number of crossings lie before it on its line along x.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

struct GridCrossing {
  double at = 0;     // coordinate along the line's axis
  int face = -1;     // cage triangle
  double bary[3]{};  // barycentric coordinates of the crossing in that triangle (sum 1, each >= 0)
};

class CageGrid {
 public:
  // Throws nothing itself; callers check the node count against their budget first (node_count).
  CageGrid(const Mesh& cage, double spacing);

  // Nodes per axis for a cage and spacing, without building anything (for budget checks).
  static Eigen::Array3i node_counts(const Mesh& cage, double spacing);

  const Eigen::Array3i& counts() const { return n_; }
  double spacing() const { return h_; }
  const Eigen::Vector3d& origin() const { return origin_; }
  long long node(int i, int j, int k) const { return (static_cast<long long>(k) * n_[1] + j) * n_[0] + i; }
  Eigen::Vector3d position(int i, int j, int k) const { return origin_ + h_ * Eigen::Vector3d(i, j, k); }
  bool inside(long long node) const { return inside_[static_cast<size_t>(node)] != 0; }

  // The crossings on the line along `axis` through node (i, j, k) strictly between its coordinate and the next
  // node's in direction `step` (+1 or -1), nearest to the node first.
  void crossings_between(int axis, int i, int j, int k, int step, std::vector<const GridCrossing*>& out) const;

  // Total crossings stored (for the memory estimate's report).
  long long crossing_count() const {
    return static_cast<long long>(crossings_[0].size() + crossings_[1].size() + crossings_[2].size());
  }

 private:
  // Index of the line along `axis` through the node with the given indices.
  long long line(int axis, int i, int j, int k) const;
  void find_crossings(const Mesh& cage, int axis);
  void classify();

  Eigen::Array3i n_;
  double h_ = 0;
  Eigen::Vector3d origin_;
  std::vector<unsigned char> inside_;
  // Per axis: the crossings of every line, sorted along it, lines one after another (offsets_[axis][line]).
  std::vector<GridCrossing> crossings_[3];
  std::vector<long long> offsets_[3];
};

}  // namespace sd
