// The drag of the real-model benchmarks (cpp/tools/bench_models.cpp; scripts/bench/models.mjs builds the same scene
// for wasm): the vertices within 5% of one end of the model's longest axis are fixed, those within 5% of the other
// end are pulled sideways (along the second-longest axis) by 8% of the bounding-box diagonal and turned about the
// third axis through their centroid.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd::tools {

struct DragScene {
  std::vector<std::vector<int>> groups;  // fixed end, moved end
  Vertices fixed, moved;                 // rest positions of each group
  Eigen::Vector3d side, turn_axis, centre;
  double diagonal = 0;
  double turn_degrees = 20;
  // The targets (one row per handle vertex, groups in order) at a fraction t of the drag (t > 1 carries it on).
  Vertices targets(double t) const {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(t * turn_degrees * M_PI / 180.0, turn_axis).toRotationMatrix();
    Vertices out(fixed.rows() + moved.rows(), 3);
    out.topRows(fixed.rows()) = fixed;
    for (Eigen::Index i = 0; i < moved.rows(); ++i) {
      const Eigen::Vector3d p = moved.row(i).transpose();
      out.row(fixed.rows() + i) = (centre + R * (p - centre) + t * 0.08 * diagonal * side).transpose();
    }
    return out;
  }
};

inline DragScene drag_scene(const Mesh& mesh, double turn_degrees = 20) {
  const Eigen::Vector3d lo = mesh.V.colwise().minCoeff(), hi = mesh.V.colwise().maxCoeff();
  const Eigen::Vector3d extent = hi - lo;
  int axes[3] = {0, 1, 2};
  std::sort(axes, axes + 3, [&](int a, int b) { return extent[a] > extent[b]; });
  DragScene s;
  s.diagonal = extent.norm();
  s.turn_degrees = turn_degrees;
  std::vector<int> fixed, moved;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    const double u = (mesh.V(i, axes[0]) - lo[axes[0]]) / extent[axes[0]];
    if (u < 0.05) fixed.push_back(static_cast<int>(i));
    else if (u > 0.95) moved.push_back(static_cast<int>(i));
  }
  s.groups = {fixed, moved};
  s.fixed.resize(static_cast<Eigen::Index>(fixed.size()), 3);
  s.moved.resize(static_cast<Eigen::Index>(moved.size()), 3);
  for (size_t k = 0; k < fixed.size(); ++k) s.fixed.row(static_cast<Eigen::Index>(k)) = mesh.V.row(fixed[k]);
  for (size_t k = 0; k < moved.size(); ++k) s.moved.row(static_cast<Eigen::Index>(k)) = mesh.V.row(moved[k]);
  s.centre = s.moved.colwise().mean().transpose();
  s.side = Eigen::Vector3d::Unit(axes[1]);
  s.turn_axis = Eigen::Vector3d::Unit(axes[2]);
  return s;
}

}  // namespace sd::tools
