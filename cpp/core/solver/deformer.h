// The stateful deformation session (libigl precompute/solve shape, CGAL-style dirty flags):
// it owns the rest mesh, the cage, W, the factorizations and the handles, re-factors only when the
// handle set or the position weight changes, and warm-starts every step from the current positions.
//
//   Deformer d(mesh, cage, bind);            // validates the pair and binds W once
//   d.set_handles({{0, 1, 2}, {57}});        // vertex groups; factorizes
//   d.set_targets(targets);                  // one row per handle vertex, groups in order; cheap
//   StepResult r = d.step(1);                // k iterations (warm start); d.positions() is the mesh
//   d.solve();                               // iterate until converged or max_iterations
//
// Handles may not be empty, overlap or be out of range: those throw sd::Error and leave the session
// unchanged. A step never produces NaN/Inf: on numerical failure the last good iterate is kept and the
// stop reason says why.
//
// Conventions: set_handles resets the targets to the handles' current positions (nothing jumps);
// changing the method resets to the rest pose (each method starts from rest, as in the comparisons of
// docs/experiments); the subspace positions are X = X0 + W (P - P0), which equals W P by linear precision
// and keeps the rest pose exact even with a float32 W.
#pragma once

#include <memory>
#include <vector>

#include "core/weights/cage_quality.h"
#include "core/weights/mean_value_coordinates.h"
#include "core/mesh/mesh.h"
#include "core/solver/solver_types.h"

namespace sd {

class Deformer {
 public:
  // Throws sd::Error (with all findings) when the mesh or cage is invalid or a vertex is outside.
  // A cage with no faces means "no cage": only the full-space method and ARAP are available.
  Deformer(const Mesh& mesh, const Mesh& cage, const MvcOptions& bind = {});
  ~Deformer();
  Deformer(const Deformer&) = delete;
  Deformer& operator=(const Deformer&) = delete;

  void set_options(const SolverOptions& options);
  const SolverOptions& options() const;

  void set_handles(const std::vector<std::vector<int>>& groups);
  const std::vector<std::vector<int>>& handles() const;
  // #handle vertices by 3, in the order of the groups' vertices.
  void set_targets(const Vertices& targets);

  StepResult step(int iterations);
  StepResult solve();
  // Back to the rest pose (handles and options are kept).
  void reset();

  const Vertices& positions() const;   // current deformed mesh, #V by 3
  Vertices cage_positions() const;     // current cage P (subspace); the rest cage for other methods
  const Mesh& rest_mesh() const;
  const Mesh& rest_cage() const;
  const WeightMatrix& weights() const;
  double rest_volume() const;
  double bind_ms() const;
  // Time of the one-off subspace precomputation B = (L W)^T (L W) (0 without a cage).
  double precompute_ms() const;
  int fallback_count() const;          // vertices whose Laplacian coordinates used the fallback
  // How well the cage controls the mesh (weights/cage_quality.h), computed on each call from W. Throws
  // sd::Error (NoCage) in a session without a cage.
  CageQuality cage_quality(const CageQualityOptions& options = {}) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sd
