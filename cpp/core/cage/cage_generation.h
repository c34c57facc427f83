// Automatic cage generation for a triangle mesh: the model as the user has it is welded (mesh_layout.h), and an
// open one closed by the fan over each hole (the surface its kept volume encloses, part_volume.h).
// Method: a voxel-dilated surface at distance >= `offset` outside the mesh (core/cage/internal/voxel_dilation.h), then
// progressive-hull decimation to the requested vertex count (core/cage/internal/progressive_hull.h; Sander et al.
// 2000), in which every collapse only grows the enclosed region and is refused if it would self-intersect or come
// within offset/2 of the mesh. The result is validated independently of how it was made (closed,
// edge/vertex-manifold, outward, no self-intersection, no crossing with the mesh, every mesh vertex at
// winding number ~1, vertex count within 20% of the target); when a check fails the whole pipeline is
// retried with a larger offset, and sd::Error is thrown when no attempt succeeds.
#pragma once

#include <functional>
#include <string>

#include "core/mesh/mesh.h"

namespace sd {

// Limits of CageOptions (generate_cage refuses beyond them, naming the limit; JS gets them through the schema).
constexpr int kMinCageVertices = 4;
constexpr int kMaxCageVertices = 20000;
constexpr int kMinCageResolution = 8;  // a resolution given (0: automatic) is at least this
constexpr int kMaxCageResolution = 512;

struct CageOptions {
  int target_vertices = 100;  // K; the cage gets K vertices (at most 20% more when collapses run out)
  double offset = 0.0;        // clearance to aim for (mesh units), at most the bounding-box diagonal;
                              // <= 0: 0.5% of the diagonal
  int resolution = 0;         // voxels along the longest bounding-box side (at most kMaxCageResolution; the
                              // voxels are never finer than offset / 8); <= 0: automatic from K
  int max_attempts = 4;       // each retry multiplies the offset by 1.6
  // Called now and then with the fraction done; return false to cancel (throws sd::Error "cancelled").
  std::function<bool(double)> progress;
};

struct CageResult {
  Mesh cage;                        // closed, manifold, outward (counter-clockwise seen from outside)
  double offset = 0.0;              // offset of the successful attempt
  double voxel_size = 0.0;          // voxel size of the successful attempt
  int attempts = 0;                 // 1 when the first attempt succeeded
  int start_vertices = 0;           // vertices of the voxel surface the hull started from
  double volume_ratio = 0.0;        // cage volume / mesh volume (0 when the mesh volume is not positive)
  double start_volume_ratio = 0.0;  // the same for the voxel surface (how much the hull added: the rest)
  double min_clearance = 0.0;       // smallest distance from a mesh vertex to the cage surface
};

// Throws sd::Error on invalid input (a mesh that check_model refuses -- non-manifold, inward, degenerate,
// non-finite, flat -- or options out of range), on cancellation, and when no attempt yields a valid cage
// (the message names the last failed check).
CageResult generate_cage(const Mesh& mesh, const CageOptions& options = {});

// The checks generate_cage applies to its result: "" when `cage` is a valid cage for `mesh`, else a
// sentence naming the first failed check (with counts and indices). `tol` is the length tolerance of the
// intersection tests.
std::string cage_defect(const Mesh& mesh, const Mesh& cage, double tol);

}  // namespace sd
