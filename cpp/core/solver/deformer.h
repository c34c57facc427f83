// The stateful deformation session (libigl precompute/solve shape; one object per method, methods/method_solver.h):
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
//
// The mesh is given as the user has it (the file's vertex layout): the session builds its MeshLayout
// (core/mesh/mesh_layout.h: split vertices welded, unreferenced ones carried along, non-manifold ones split)
// and solves on that layout's solver mesh, while everything it takes and gives per vertex or per triangle --
// handles, targets, positions, volume parts, rest_mesh() -- is in the file's numbering. An open mesh keeps its
// capped volume; several components keep one volume each (the default volume parts).
//
// The subspace is the cage's (W: mean value coordinates by default, or the positive mean value or harmonic
// coordinates of BasisOptions::coordinates, basis/cage_coordinates.h) or, with BasisKind::Spectral, the mesh's
// own low-frequency basis B (spectral_basis.h; no cage needed): the solver treats B exactly as W, with the
// coefficients C in place of the cage vertices P (X = X0 + B (C - C0)).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/arap/arap.h"
#include "core/mesh/mesh.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/mesh_layout.h"
#include "core/skeleton/skeleton.h"
#include "core/solver/handle_line.h"
#include "core/solver/solver_types.h"
#include "core/basis/cage_quality.h"
#include "core/basis/cage_coordinates.h"
#include "core/basis/mean_value_coordinates.h"
#include "core/basis/spectral_basis.h"

namespace sd {

enum class BasisKind { Cage, Spectral };

// The basis of the subspace method, chosen when the session is made (it is bound once, like W).
struct BasisOptions {
  BasisKind kind = BasisKind::Cage;
  MvcOptions cage;                 // Cage: binding W to the cage given to the Deformer
  CoordinatesOptions coordinates;  // Cage: which coordinates W holds (mean value by default)
  SpectralOptions spectral;        // Spectral: spectral.modes >= 1; the cage, if any, is only kept for rest_cage()
  LayoutOptions layout;  // how the mesh is welded (mesh_layout.h); not a basis option, but made at the same time
};

// The reduced integration's rule (SolverOptions::integration; docs/method.md section 17), once it is made.
struct ReducedIntegrationInfo {
  bool fitted = false;
  // "every vertex" (a mesh of at most max(800, 2m) vertices: the sum is exact) or "clusters" (one rotation per
  // cluster of vertices, rotation_clusters.h).
  std::string rule;
  int samples = 0;     // the vertices the rule reads: every one, or the clusters' centres
  int candidates = 0;  // the mesh's vertices
  // The rule's gradient against the full term's on held-out poses of the subspace (relative; 0 when exact).
  double test_error = 0;
  // test_error <= kReducedTestErrorLimit. When not, the rule misses what the full term sees and a reduced
  // solve may converge to another shape: the CLI warns (code reduced_integration_inaccurate) and the app keeps full
  // integration while dragging.
  bool reliable = false;
  double ms = 0;  // time to make the rule
};

class Deformer {
 public:
  // Throws sd::Error (with all findings, check_model_in_cage) when the mesh or cage is invalid or a vertex is
  // outside.
  // A cage with no faces means "no cage": only the full-space method and ARAP are available.
  Deformer(const Mesh& mesh, const Mesh& cage, const MvcOptions& bind = {});
  // With BasisKind::Spectral only the mesh is checked and the subspace method is available without a cage (and
  // is the default method). Throws sd::Error as spectral_basis does (modes, memory, cancellation).
  Deformer(const Mesh& mesh, const Mesh& cage, const BasisOptions& basis);
  ~Deformer();
  Deformer(const Deformer&) = delete;
  Deformer& operator=(const Deformer&) = delete;

  void set_options(const SolverOptions& options);
  const SolverOptions& options() const;

  void set_handles(const std::vector<std::vector<int>>& groups);
  const std::vector<std::vector<int>>& handles() const;
  // #handle vertices by 3, in the order of the groups' vertices.
  void set_targets(const Vertices& targets);
  // The projection constraint (handle_line.h): one line per handle group (empty: every group a point target).
  // A group with a line needs each vertex only on the line through its target; its depth is the energy's. Cheap
  // (no refactoring; an app sends the camera's lines with each drag). set_handles clears them. The Gauss-Newton
  // methods (subspace and full space, full and reduced integration) honour them; ARAP pins every handle vertex to
  // its target, as before. Throws sd::Error (lines unchanged) on a wrong count or an unusable line.
  void set_handle_lines(const std::vector<HandleLine>& per_group);
  const std::vector<HandleLine>& handle_lines() const;
  // Per group, the largest distance of its vertices from their lines (from their targets for a point target).
  Eigen::VectorXd handle_distances() const;

  // Volume kept per part (part_volume.h): one part index per triangle of the file, parts 0 .. K-1 (partition.h
  // makes them from vertex or triangle lists). The volume constraint becomes K constraints, one per part; an
  // empty list restores the default: one part per connected component (default_volume_parts), which for one
  // closed component is the single global volume. Throws sd::Error (session unchanged) on a bad partition.
  // Positions are kept; the next step restores the parts' rest volumes.
  void set_volume_parts(const std::vector<int>& part_of_face);
  std::vector<int> volume_parts() const;  // per file triangle; empty: the single global volume
  // The skeleton (skeleton.h; docs/method.md section 5.4): joints inside the mesh (world coordinates of the rest
  // mesh) and bones between them. Every Gauss-Newton solve (subspace and full space, full and reduced integration)
  // then keeps each bone's length and its midpoint on the middle of the segment between its joints as hard
  // constraints beside the volume (a midpoint only where the method's space can represent it independently:
  // SkeletonReport's straight_hard); ARAP ignores it. The joints follow the mesh by its own mean value coordinates.
  // An empty skeleton removes it. Throws sd::Error (InvalidSkeleton; skeleton unchanged) on joints outside the
  // mesh, bad bones, an open mesh, or bone lengths the subspace cannot keep independently. Positions are kept: the
  // next step restores the lengths from wherever the mesh is. With the option straightness_weight above 0 the soft
  // straightness term comes with the skeleton, and the current method is re-factored for it.
  void set_skeleton(const Skeleton& skeleton);
  Skeleton skeleton() const;
  // The deformed joints and per bone its length and straightness errors and multiplier; none without a skeleton.
  std::optional<SkeletonReport> skeleton_report() const;
  // V_k(X0) per part (psi(X0) alone without parts) and V_k at the current positions.
  Eigen::VectorXd rest_part_volumes() const;
  Eigen::VectorXd part_volumes() const;

  StepResult step(int iterations);
  StepResult solve();
  // Step-through of ARAP (method arap, with handles): one half of the next local-global iteration from the
  // current positions, without acceleration: the local step (the best rotations; positions unchanged) or the
  // global step (the positions for those rotations). Throws sd::Error with another method or no handles.
  ArapHalfStep arap_half_step(bool local);
  // Back to the rest pose (handles and options are kept).
  void reset();

  const Vertices& positions() const;  // current deformed mesh in the file's layout, #V by 3
  // Current cage P (subspace method with the cage basis); the rest cage otherwise.
  Vertices cage_positions() const;
  // The subspace coefficients: P with the cage basis, C (k + 4 by 3) with the spectral one; the rest ones
  // (P0 or C0) while another method runs.
  const Eigen::MatrixXd& subspace_coefficients() const;
  const Mesh& rest_mesh() const;     // the mesh as given (file layout)
  const MeshLayout& layout() const;  // its solver mesh and the maps (mesh_layout.h)
  const Mesh& rest_cage() const;
  BasisKind basis_kind() const;
  // The subspace basis: W (#V by m) or B (#V by k + 4); empty without one.
  const BasisMatrix& basis() const;
  // Spectral basis: lambda_0 (~0) .. lambda_k of -L phi = lambda M phi; empty for the cage.
  const Eigen::VectorXd& basis_eigenvalues() const;
  double rest_volume() const;
  // Time of binding the basis: W's mean value coordinates, or B's eigen-decomposition and orthonormalisation.
  double bind_ms() const;
  // What binding the cage's W found (its coordinate type, smallest weight, and the type's own figures).
  const CoordinatesReport& coordinates_report() const;
  // Time of the one-off subspace precomputation: B = (L W)^T (L W) and, with a cage, the cage
  // regularisation's W^T W (0 without a subspace).
  double precompute_ms() const;
  int fallback_count() const;  // vertices whose Laplacian coordinates used the fallback
  // Warnings about the current result (mesh/deformation_check.h): folded triangles (named in the file's
  // numbering) and, in the cage subspace, a deformed cage that crosses itself. O(#triangles + cage pairs).
  std::vector<Finding> result_findings() const;
  // The reduced integration's fit: made on the first solve with `integration: reduced` (or by prepare_reduced),
  // kept until the weighting changes.
  ReducedIntegrationInfo reduced_integration() const;
  void prepare_reduced();
  // Makes the full integration's factor preconditioner's pose-free parts now (the stiffest vertices, the rotation
  // clusters) where the options would let a solve buy it (method subspace, preconditioner gauss-newton); else
  // nothing. Kept until the weighting changes, like the rule; the app makes both after a model loads.
  void prepare_factor();
  // Whether those parts are made (by prepare_factor or by a solve that bought the factor) and kept.
  bool factor_prepared() const;
  // The energy and merit summed over every vertex at the current positions (whatever the integration), for
  // reporting what a reduced solve reached: 1/2 |f|^2 + the cage regularisation (the merit adds lambda g, zero
  // where the volume is restored).
  double full_energy() const;
  // How well the cage controls the mesh (basis/cage_quality.h), computed on each call from W. Throws
  // sd::Error (NoCage) in a session without a cage or with the spectral basis.
  CageQuality cage_quality(const CageQualityOptions& options = {}) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sd
