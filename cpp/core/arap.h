// As-rigid-as-possible surface deformation (Sorkine and Alexa 2007): local step = per-vertex best
// rotation by 3x3 SVD (reflection-safe), global step = sparse Cholesky solve with the handle vertices as
// hard constraints, factorized once per handle set. Warm-started from the previous positions.
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <vector>

#include "core/mesh.h"
#include "core/solver_types.h"

namespace sd {

class ArapSolver {
 public:
  ArapSolver(const Vertices& X0, const Faces& F);
  ~ArapSolver();

  // Factorizes the global system for this handle set (sorted, unique, in range; checked by caller).
  void set_handles(const std::vector<int>& handle_vertices);

  // One local-global iteration from X (updated in place); targets has one row per handle vertex in the
  // order given to set_handles. Returns the ARAP energy after the step in stats.energy/merit.
  IterationStats iterate(Vertices& X, const Vertices& targets);

  double energy(const Vertices& X) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sd
