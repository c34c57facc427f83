// Scenes shared by the reduced integration's tests (reduced_subspace_test.cpp, finishing_integration_test.cpp).
#pragma once

#include <vector>

#include "core/mesh/examples.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/solver_types.h"

namespace sd::test {

// A built-in example with its ends along x as handles (8% of the length each), the right end moved by `move`.
struct BarScene {
  Example bar;
  std::vector<std::vector<int>> groups;
  Vertices targets;
  explicit BarScene(const Eigen::RowVector3d& move, const char* example = "bar") : bar(make_example(example)) {
    const double lo = bar.mesh.V.col(0).minCoeff(), hi = bar.mesh.V.col(0).maxCoeff(), length = hi - lo;
    groups.resize(2);
    for (int i = 0; i < bar.mesh.V.rows(); ++i) {
      if (bar.mesh.V(i, 0) < lo + 0.08 * length) groups[0].push_back(i);
      if (bar.mesh.V(i, 0) > hi - 0.08 * length) groups[1].push_back(i);
    }
    targets.resize(static_cast<Eigen::Index>(groups[0].size() + groups[1].size()), 3);
    Eigen::Index r = 0;
    for (int v : groups[0]) targets.row(r++) = bar.mesh.V.row(v);
    for (int v : groups[1]) targets.row(r++) = bar.mesh.V.row(v) + move;
  }
  // Sets the handles and targets on an energy of the bar's mesh.
  void hold(DeformationEnergy& energy) const {
    std::vector<int> flat, sizes;
    for (const auto& g : groups) {
      flat.insert(flat.end(), g.begin(), g.end());
      sizes.push_back(static_cast<int>(g.size()));
    }
    energy.set_handles(flat, sizes);
    energy.set_targets(targets);
  }
};

// Options with this integration and Jacobian mode, the rest defaults.
inline SolverOptions with(Integration integration, JacobianMode mode) {
  SolverOptions o;
  o.integration = integration;
  o.jacobian = mode;
  return o;
}

}  // namespace sd::test
