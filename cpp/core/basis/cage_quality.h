// How well a cage controls its mesh, read from the bound weights W (n mesh vertices by m cage vertices),
// so that a page or the CLI can warn about a poor cage before the user drags it (docs/cage.md, "Cage
// quality"). Three numbers:
//   - weak vertices: cage vertices whose largest weight on any mesh vertex is below `weak_weight`; moving
//     one of them barely moves the mesh.
//   - influence ratio: smallest / largest eigenvalue of W^T W / n. A tiny ratio means some combination of
//     cage motions barely moves the mesh (a whole region of the cage far from it, or cage vertices that
//     cancel each other). The subspace problem is then nearly free in those directions: without the cage
//     regularisation (solver/internal/energy/cage_regularization.h) the deformed cage drifts far while the mesh
//     looks fine; with it those motions follow the cage's affine fit, so the cage stays together but gives
//     no control there. It flags cages whose every vertex still has some weight (the per-vertex count
//     misses those).
//   - volume ratio: cage volume / mesh volume (a huge ratio: a loose cage, little control); the mesh's volume is
//     the one the solver keeps (enclosed_volume: an open mesh's with its holes capped).
// Each exceeded threshold adds a sentence to `warnings`; no warning means nothing looked poor.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/basis/basis_matrix.h"

namespace sd {

struct CageQualityOptions {
  double weak_weight = 1e-3;          // a cage vertex with no weight above this is "weak"
  double max_weak_fraction = 0.1;     // warn when more than this fraction of the cage vertices is weak
  double min_influence_ratio = 1e-6;  // warn below this influence ratio
  double max_volume_ratio = 20;       // warn above this cage / mesh volume ratio
  // W^T W is summed over at most this many rows of W (every k-th row, a fixed stride): O(rows m^2), but
  // over at least rows_per_vertex x m rows: with fewer, the sampled matrix can look nearly singular when W
  // is not (the 342-vertex handbones cage: influence ratio 2e-6 from 2749 of its 5497 rows, 3e-4 from all).
  int sample_rows = 8192;
  int rows_per_vertex = 24;
  // The influence ratio needs an m x m symmetric eigen-solve (O(m^3)); above this cage size it is skipped.
  int max_spectrum_vertices = 400;
};

struct CageQuality {
  int cage_vertices = 0;
  int weak_vertices = 0;      // columns j with max_i |W_ij| < weak_weight
  double min_column_max = 0;  // min over j of max_i |W_ij|
  double volume_ratio = 0;    // cage volume / mesh volume
  // Smallest / largest eigenvalue of the sampled W^T W; NaN when not computed (cage too large, no rows).
  double influence_ratio = std::numeric_limits<double>::quiet_NaN();
  int weak_motions = 0;               // eigenvalues below min_influence_ratio x the largest
  int sampled_rows = 0;               // rows of W in the sampled W^T W
  double ms = 0;                      // time taken
  std::vector<std::string> warnings;  // one sentence per exceeded threshold
  // The code of each warning, in the same order: weak_cage_vertices, weak_cage_motions, loose_cage.
  std::vector<std::string> warning_codes;
  bool poor() const { return !warnings.empty(); }
};

// Throws sd::Error when W's size does not match the mesh and cage.
CageQuality cage_quality(const BasisMatrix& W, const Mesh& mesh, const Mesh& cage,
                         const CageQualityOptions& options = {});

}  // namespace sd
