// The arm of issue 30 (docs/experiments/skeleton.md), shared by the skeleton's tests.
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "core/mesh/shapes.h"
#include "core/skeleton/skeleton.h"
#include "core/solver/solver_types.h"
#include "solver_fixtures.h"

namespace sd::test {

// The arm: a capsule of length 5 (a 4-long cylinder, radius 0.5) in its 28-vertex bar cage, the left end held,
// the right end folded down by (-1.2, -2.2, 0); bones at x = -2, 0, 2.
// Another mesh may stand for the capsule (a finer one, say): the handles and targets are chosen the same way.
struct Arm {
  Mesh mesh;
  Mesh cage = make_bar_cage(-2.9, 2.9, 0.8, 0.8, 6);
  std::vector<std::vector<int>> groups;
  Vertices targets;
  Skeleton skeleton;

  explicit Arm(Mesh capsule = make_capsule(4.0, 0.5, 4, 16, 12)) : mesh(std::move(capsule)) {
    groups.push_back(test::vertices_where(mesh, [](const Eigen::RowVector3d& p) { return p.x() < -2.2; }));
    groups.push_back(test::vertices_where(mesh, [](const Eigen::RowVector3d& p) { return p.x() > 2.2; }));
    targets.resize(static_cast<Eigen::Index>(groups[0].size() + groups[1].size()), 3);
    Eigen::Index r = 0;
    for (size_t g = 0; g < 2; ++g)
      for (int v : groups[g])
        targets.row(r++) = mesh.V.row(v) + (g == 1 ? Eigen::RowVector3d(-1.2, -2.2, 0) : Eigen::RowVector3d::Zero());
    skeleton.joints.resize(3, 3);
    skeleton.joints << -2, 0, 0, 0, 0, 0, 2, 0, 0;
    skeleton.bones = {{0, 1}, {1, 2}};
  }
};

// Options of one method, step and integration, with room to converge.
inline SolverOptions method(Method m, JacobianMode mode = JacobianMode::Fast,
                            Integration integration = Integration::Full) {
  SolverOptions o;
  o.method = m;
  o.jacobian = mode;
  o.integration = integration;
  o.max_iterations = 200;
  return o;
}

// The mesh moved off its rest pose by a smooth wobble of the given size (no symmetry to hide a wrong sign).
inline Vertices wobbled(const Mesh& mesh, double amount) {
  Vertices X = mesh.V;
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    X.row(i) += amount * Eigen::RowVector3d(std::sin(3.0 * i), std::cos(1.0 * i), std::sin(0.5 * i + 1));
  return X;
}

// A fixed block of directions, rows by cols, for finite differences and products.
inline Eigen::MatrixXd fixed_directions(Eigen::Index rows, Eigen::Index cols) {
  Eigen::MatrixXd V(rows, cols);
  for (Eigen::Index i = 0; i < V.size(); ++i) V.data()[i] = std::sin(0.37 * i + 0.2);
  return V;
}

}  // namespace sd::test
