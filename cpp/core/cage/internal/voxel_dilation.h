// A closed, manifold, outward surface at a guaranteed distance outside a mesh: the starting point of cage
// generation (core/cage/cage_generation.h).
//   1. Mark the voxels the mesh surface passes through (triangles sampled at half the voxel size).
//   2. Dilate: fill every voxel whose centre is within offset + sqrt(3)/2 h of the mesh (exact point-triangle
//      distance, AABB tree; candidates are the voxels near a marked one, found by an exact Euclidean distance
//      transform of the grid, so the cost does not grow with the offset). Every point within `offset` of
//      the mesh lies in such a voxel, so the boundary keeps at least `offset` from the mesh (h = voxel size).
//   3. Fill the inside and every cavity (flood fill of the outside from the padded grid border).
//   4. Make the voxel set well-composed (Latecki 1997): fill the 2x2 and 2x2x2 configurations whose
//      boundary would be non-manifold (two voxels, or two empty cells, touching only along an edge or at a
//      corner). Only filling, so the distance guarantee holds; repeated with step 3 until stable.
//   5. Emit the boundary quads between filled and empty voxels, two triangles each, outward.
// The result is closed, edge- and vertex-manifold and free of self-intersections; it may have several
// components (one per separated part of the mesh) and a genus below the mesh's (holes narrower than about
// 2 * offset are closed).
#pragma once

#include <functional>

#include "core/mesh/mesh.h"

namespace sd {

// `offset` > 0 and `voxel_size` > 0 are lengths in the mesh's units. Throws sd::Error when the grid would
// exceed `max_cells` voxels (checked before anything is allocated). `progress`, when given, is called with
// the fraction done; returning false cancels (sd::Error "cage generation cancelled").
Mesh dilated_voxel_surface(const Mesh& mesh, double offset, double voxel_size, long long max_cells = 64LL << 20,
                           const std::function<bool(double)>& progress = {});

}  // namespace sd
