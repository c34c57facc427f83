// Vertex normals for drawing a deformed mesh, in the file's numbering: each triangle's cross product
// (unnormalised, so larger triangles count more, as three.js's computeVertexNormals weights them) summed over
// the triangles around each smoothing group, then made unit length. A smoothing group is a set of file vertices
// that share one normal (the copies of a welded point whose rest normals agree; web/lib/normals.js makes them);
// a vertex whose sum vanishes keeps its fallback normal (the file's own) when it has one, else (0, 0, 0).
// Deterministic: per-triangle normals and per-group sums in a fixed order, on the thread pool.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

class VertexNormals {
 public:
  // vertex_count file vertices, faces: the file's triangles; group[v]: the smoothing group of file vertex v
  // (in [0, vertex_count); empty: every vertex its own); fallback: 3 floats per vertex, NaN where the file has none
  // (empty: none at all). Throws sd::Error when the sizes do not fit.
  VertexNormals(int vertex_count, const Faces& faces, std::vector<int> group, std::vector<float> fallback);

  // Unit normals of the vertices at positions X (n x 3), as 3 n floats.
  void compute(const Vertices& X, std::vector<float>& out) const;

 private:
  Faces faces_;
  std::vector<int> group_;
  std::vector<float> fallback_;
  // For each group, the triangles around its vertices, one entry per corner (a triangle with two corners in a
  // group counts twice, as summing per corner does): offsets_ into corners_.
  std::vector<int> offsets_;
  std::vector<int> corners_;
  mutable Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> face_normals_;
  mutable Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> group_sums_;
};

}  // namespace sd
