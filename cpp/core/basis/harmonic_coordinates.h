// Harmonic coordinates (Joshi, Meyer, DeRose, Green and Sanocki 2007, "Harmonic coordinates for character
// articulation") of points with respect to a closed, outward triangle cage: for each cage vertex j, the
// function h_j harmonic inside the cage (Laplace's equation) with boundary values phi_j (its hat function,
// linear on each cage triangle); W_ij = h_j(x_i).
//   W is #points by #cage vertices; entries >= 0 (the discrete maximum principle, to the solver's rounding),
//   rows sum to 1 (to rounding) and W P0 = points to within the grid's resolution (exactly at grid nodes).
//
// Discretisation (docs/method.md section 19): a regular grid of spacing h over the cage; the unknowns are the
// grid nodes inside the cage. Each node's 6 arms reach a neighbouring node, or the cage where it crosses the arm
// at a fraction alpha of h (its value there: the crossing's barycentric coordinates in its triangle, i.e.
// phi_j at the crossing). Per node, sum over arms of (u_node - u_end) / alpha_arm = 0: symmetric, positive
// definite, an M-matrix (so values stay within the boundary values' range: >= 0 and, summed over j, exactly 1),
// and exact for linear functions (so sum_j h_j p_j = x at every node). One sparse LDL^T factorization serves all
// m right-hand sides, solved in blocks of columns on the thread pool. At a mesh vertex W is interpolated
// trilinearly from its grid cell's corners; a corner outside the cage takes the boundary value where an arm
// from an inside neighbour leaves the cage (else the cage's nearest point): inside such cells linear precision
// holds to about the cell size.
#pragma once

#include "core/mesh/mesh.h"
#include "core/basis/mean_value_coordinates.h"
#include "core/basis/basis_matrix.h"

namespace sd {

struct HarmonicOptions {
  // Grid cells along the longest side of the cage's bounding box; 0: chosen from the cage (about
  // kDefaultInteriorNodes grid nodes inside it, within [kMinResolution, kDefaultMaxResolution]).
  int resolution = 0;
  static constexpr int kMinResolution = 8;
  static constexpr int kMaxResolution = 1024;
  static constexpr int kDefaultMaxResolution = 192;
  static constexpr double kDefaultInteriorNodes = 20000;
  // The work allowed (multiply-adds of the factorization and the solves, HarmonicReport::work): a resolution
  // over it is refused before the grid is built (from a lower bound) or before the factor is computed (counted),
  // naming a resolution that fits. The default is about 10 s natively and up to a minute in wasm on the shared
  // machine (docs/method.md section 19); 0: no limit (a caller that asks for a long binding explicitly).
  double max_work = kDefaultMaxWork;
  static constexpr double kDefaultMaxWork = 1e10;
};

struct HarmonicReport {
  int resolution = 0;          // cells along the longest side of the cage's box
  int grid[3] = {0, 0, 0};     // nodes per axis
  double spacing = 0;          // h
  int unknowns = 0;            // grid nodes inside the cage
  double factor_nonzeros = 0;  // entries of the LDL^T factor below its diagonal
  double work = 0;             // multiply-adds of the factorization and the solves
  double bytes = 0;            // peak memory besides W: grid, factor, right-hand side blocks
  int boundary_cells = 0;      // mesh vertices in a grid cell with a corner outside the cage
  int unresolved = 0;          // of those, the vertices whose cell has no corner inside the cage
  double factor_seconds = 0;
  double solve_seconds = 0;
};

// The resolution harmonic_coordinates uses for this cage with these options (resolution 0: chosen).
int harmonic_resolution(const Mesh& cage, const HarmonicOptions& options);

// W (#points by #cage vertices). Throws sd::Error: MemoryBudget (checked before the grid is built, from the
// cage's volume and a lower bound of the factor, and again before the factor is allocated, counted after the
// ordering: W, the grid, the factor and the solve's blocks together against binding's budget, naming the
// megabytes and a resolution that fits; an allocation that fails anyway is a MemoryBudget error too),
// InvalidArgument for a resolution outside [8, 1024] or whose work is over options.max_work (checked at the
// same two points, naming a resolution that fits), MeshOutsideCage for points outside, InvalidMesh for a bad
// cage, Cancelled when binding.progress returns false.
// Progress: after the grid and ordering (0.02), during the factorization (every few tens of milliseconds), then
// after each round of right-hand side blocks; the grid and the ordering themselves report nothing (bounded by
// the checks before them: a few seconds at most).
BasisMatrix harmonic_coordinates(const Vertices& points, const Mesh& cage, const MvcOptions& binding,
                                 const HarmonicOptions& options = {}, MvcReport* report = nullptr,
                                 HarmonicReport* details = nullptr);

}  // namespace sd
