// Shared mesh types. Everything in the core uses these shapes.
//   Vertices: #V by 3, row-major, so a Vertices maps with no copy onto an interleaved xyz buffer
//             (the JS side's Float64Array) and a flattened coordinate index is 3 * vertex + axis.
//   Faces:    #F by 3 vertex indices, row-major, counter-clockwise seen from outside (outward normals).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products everywhere
#include <vector>

namespace sd {

using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct Mesh {
  Vertices V;
  Faces F;
};

// Length of the diagonal of the axis-aligned bounding box (0 for an empty mesh). Tolerances that must
// not depend on the model's units are taken relative to it.
double bounding_box_diagonal(const Vertices& V);

// The axis-aligned box of each group of triangles' corners (group_of_face: one index in [0, count) per row of F), as
// rows [min x, min y, min z, max x, max y, max z]; a group without triangles has min +inf and max -inf. Triangles
// with an index out of range (of V or of the groups) are left out.
Eigen::Matrix<double, Eigen::Dynamic, 6> group_boxes(const Vertices& V, const Faces& F,
                                                     const std::vector<int>& group_of_face, int count);

}  // namespace sd
