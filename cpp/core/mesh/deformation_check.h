// Warnings about a deformed result that the solver itself does not prevent, with stable codes (the CLI's report
// and the app show them):
//   folded_triangles       the surface folds over: triangles on an edge whose two faces turned against each
//                          other by more than 90 degrees beyond their rest angle (the signed dihedral angle,
//                          so a rigid motion or a smooth bend never counts), or whose area collapsed below 1e-12
//                          of its rest area;
//   cage_self_intersecting the deformed cage crosses itself (face pairs, up to 100 counted): mean value
//                          coordinates are only meaningful in a cage that does not (the rest cage must not).
#pragma once

#include <vector>

#include "core/mesh/mesh.h"
#include "core/mesh/mesh_check.h"

namespace sd {

struct FoldCount {
  int folded_triangles = 0;  // triangles on at least one folded edge, or collapsed
  std::vector<int> first;    // the first few of them
};

// rest: the mesh at rest; X: its deformed positions (same vertex count).
FoldCount folded_triangles(const Mesh& rest, const Vertices& X);

// Findings (warnings) for a deformed mesh and, when the cage has faces, its deformed cage P. `names` gives the
// file's triangle numbers (MeshLayout::names); null: the mesh's own.
std::vector<Finding> check_deformation(const Mesh& rest, const Vertices& X, const Mesh& rest_cage, const Vertices& P,
                                       const IndexNames* names = nullptr);

}  // namespace sd
