// As-rigid-as-possible surface deformation (Sorkine and Alexa 2007): local step = per-vertex best
// rotation by 3x3 SVD (reflection-safe), global step = sparse Cholesky solve with the handle vertices as
// hard constraints, factorized once per handle set. Warm-started from the previous positions.
// Optionally Anderson-accelerated (Peng et al. 2018; anderson_acceleration.h): the extrapolated positions
// are kept only when their ARAP energy is below that of the previous iterate, otherwise the plain
// local-global result is, so the energy still never increases at fixed targets.
//
// Energy (Sorkine and Alexa eq. 3, with full weights on both half-edges):
//   E(X) = min_R sum_i sum_{j in N(i)} w_ij |(x_i - x_j) - R_i (x0_i - x0_j)|^2.
// Weights: w_ij = the rest cotangent weights L_ij = (cot a_ij + cot b_ij) / 2 of core/cotan_laplacian,
// with negative ones and those below a small positive floor (1e-3 times the mean |w|; right angles in
// quad-split grids give exact zeros) raised to that floor; the count is clamped_weight_count(). Why: with all w_ij > 0
// the energy is a sum of squares (bounded below by 0, so "never increases" means convergence), each covariance is a
// positively weighted sum, and the free block of the global matrix is a weighted graph Laplacian with a fixed vertex
// per component, i.e. an irreducibly diagonally dominant M-matrix: positive definite on any mesh quality. (The
// unclamped cotangent matrix is also positive semidefinite, but its per-vertex terms can be negative.) Shapes: Vertices
// are #V by 3 (row-major); handle targets one row per handle vertex.
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/solver/solver_types.h"

namespace sd {

// The rotation R maximizing trace(R S) for a covariance S = sum_j w_j e0_j e_j^T (so R e0_j ~ e_j):
// R = V U^T from S = U Sigma V^T, with the column of the smallest singular value flipped when that
// would be a reflection (det < 0). Zero, tiny or non-finite covariances give the identity; the result
// is always a proper rotation with finite entries.
Eigen::Matrix3d arap_best_rotation(const Eigen::Matrix3d& covariance);

// One half of a local-global iteration, for a student stepping through it (the app's step-through): the
// energies sum_i sum_j w_ij |(x_i - x_j) - R_i (x0_i - x0_j)|^2 with the rotations and positions before and
// after the half step (each half lowers it, or keeps it), and what the half changed.
struct ArapHalfStep {
  bool local = true;  // the local step (rotations) or the global one (positions)
  double energy_before = 0;
  double energy_after = 0;
  double mean_rotation = 0;  // the mean and largest angle (radians) of the vertices' rotations after the half
  double max_rotation = 0;
  double step = 0;  // global: the largest vertex move; local: 0 (positions do not change)
};

class ArapSolver {
 public:
  // Throws sd::Error on a degenerate triangle or an out-of-range index (from the cotangent weights).
  ArapSolver(const Vertices& X0, const Faces& F);
  ~ArapSolver();

  // Factorizes the global system for this handle set (sorted, unique, in range; re-checked here, throws
  // sd::Error). Connected components that contain no handle are left where X has them (their system
  // would be singular); with no handle at all iterate() only reports the energy.
  void set_handles(const std::vector<int>& handle_vertices);

  // One local-global iteration from X (updated in place); targets has one row per handle vertex in the
  // order given to set_handles. Returns the ARAP energy after the step in stats.energy/merit.
  // Handle rows of X are set exactly to their targets.
  IterationStats iterate(Vertices& X, const Vertices& targets);

  double energy(const Vertices& X) const;

  // The two halves of iterate() one at a time (no Anderson acceleration). Local: the best rotation of every
  // vertex for X, which stays as it is; "before" uses the rotations of the last local step (the identity at
  // first). Global: X becomes the positions for those rotations (handle rows set to their targets, one row
  // per handle vertex as in iterate()); "before" is with the handles already at their targets, the energy the
  // solve lowers. A following iterate() starts from what they left.
  ArapHalfStep local_half_step(const Vertices& X);
  ArapHalfStep global_half_step(Vertices& X, const Vertices& targets);

  // Anderson acceleration over the last `depth` iterations (0: plain local-global). Default 5.
  void set_acceleration(int depth);
  // Iterations whose extrapolation was rejected (energy not lower) since construction.
  int rejected_accelerations() const;

  // Per-vertex rotations of the last local step (after iterate(): the best rotations for the new X).
  const std::vector<Eigen::Matrix3d>& rotations() const;
  int clamped_weight_count() const;
  double factorization_ms() const;  // time of the last set_handles

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sd
