// ARAP (Sorkine and Alexa 2007; docs/method.md section 13) as a method: local-global iterations over the mesh with
// the energy's handle vertices (the user's, then the anchors of components none holds) pinned at their targets. The
// Laplacian-coordinate energy, the volume and a skeleton are not ARAP's: its iterations report the volume only.
#pragma once

#include <memory>
#include <vector>

#include "core/arap/arap.h"
#include "core/arap/arap_stopping_rule.h"
#include "core/mesh/mesh.h"
#include "core/solver/methods/method_solver.h"

namespace sd {

class ArapMethod : public MethodSolver {
 public:
  // Keeps references to the rest mesh and the energy (which must outlive this). The solver is made on first use.
  ArapMethod(const Mesh& mesh, const DeformationEnergy& energy) : mesh_(&mesh), energy_(&energy) {}

  StepResult run(GaussNewtonState& state, int k, const SolverOptions& options, StopCode cap) override;
  // One half of an iteration (arap.h): the local rotations for state.X (local), or the global solve that moves it.
  ArapHalfStep half_step(GaussNewtonState& state, bool local, const SolverOptions& options);
  // The stopping rule compares an iteration's energy with the last one's: forgotten when the targets, handles or
  // positions change.
  void forget_history() override { stopping_.reset(); }

 protected:
  void rebuild(const SolverOptions& options) override;

 private:
  std::vector<int> order() const;  // the energy's handle rows sorted by vertex: ARAP takes its handles sorted
  Vertices targets() const;        // the targets in that order

  const Mesh* mesh_;
  const DeformationEnergy* energy_;
  std::unique_ptr<ArapSolver> solver_;
  ArapStoppingRule stopping_;
};

}  // namespace sd
