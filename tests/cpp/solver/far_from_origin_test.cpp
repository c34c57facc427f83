// A model far from the origin deforms as it does at the origin, moved. The volume constraint, its gradient and the
// restoring cubic are summed about the rest mesh's bounding-box centre (docs/method.md section 5): summed about
// the origin, the terms of a model 1e3 away were 1e9 times its volume, and the solve stopped "stalled" after one
// iteration with nothing moved (1e2 still worked). Every Gauss-Newton mode, with the one global volume and with
// volume parts (caps between them), and an open mesh (its hole capped): the same shape to 5e-6 of the diagonal,
// the volume kept to 1e-9.
#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <vector>

#include "core/parts/part_volume.h"
#include "core/solver/deformer.h"
#include "solver_fixtures.h"
#include "test_support.h"

namespace sd {
namespace {

using test::Combo;
using test::kCombos;
using test::Scene;

struct Answer {
  StepResult result;
  Vertices positions;
  Eigen::VectorXd part_volumes;  // V_k at the answer (the one volume without parts)
  Eigen::VectorXd rest_volumes;
};

Answer solve(const Scene& s, const Eigen::RowVector3d& by, const Combo& c, const std::vector<int>& parts) {
  Deformer d(test::translated(s.mesh, by), test::translated(s.cage, by));
  SolverOptions o;
  o.method = c.method;
  o.jacobian = c.mode;
  o.max_iterations = 200;
  d.set_options(o);
  if (!parts.empty()) d.set_volume_parts(parts);
  d.set_handles(s.groups);
  d.set_targets(s.targets.rowwise() + by);
  Answer a;
  a.result = d.solve();
  a.positions = d.positions().rowwise() - by;
  a.part_volumes = d.part_volumes();
  a.rest_volumes = d.rest_part_volumes();
  return a;
}

// The capsule's right end pulled up and out; 1e3 and 1e5 away along a diagonal that mixes the axes.
void expect_the_same_shape_far_away(const Scene& s, const std::vector<int>& parts, const std::string& what) {
  const double diagonal = bounding_box_diagonal(s.mesh.V);
  for (const Combo& c : kCombos) {
    const Answer here = solve(s, Eigen::RowVector3d::Zero(), c, parts);
    ASSERT_TRUE(here.result.converged) << what << ", " << c.name << ": " << here.result.stop_reason;
    for (double offset : {1e3, 1e5}) {
      const Answer far = solve(s, Eigen::RowVector3d(offset, -0.7 * offset, 0.4 * offset), c, parts);
      const std::string name = what + ", " + c.name + " at " + std::to_string(offset);
      EXPECT_TRUE(far.result.converged) << name << ": " << far.result.stop_reason;
      // The solves stop by their tolerances, and the rounding of coordinates 1e5 away (1e-11) moves where: by up
      // to 9e-7 of the diagonal measured (the open capsule, full/fast), 1e-13 where they stop alike.
      const double moved = (far.positions - here.positions).rowwise().norm().maxCoeff() / diagonal;
      EXPECT_LE(moved, 5e-6) << name;
      const Eigen::VectorXd kept = (far.part_volumes - far.rest_volumes).cwiseQuotient(far.rest_volumes);
      EXPECT_LE(kept.cwiseAbs().maxCoeff(), 1e-9) << name;
      EXPECT_LE((far.rest_volumes - here.rest_volumes).cwiseAbs().maxCoeff(), 1e-9 * here.rest_volumes.sum()) << name;
      std::cout << "[          ] " << name << ": " << far.result.iterations.size() << " iterations ("
                << here.result.iterations.size() << " at the origin), shape " << moved
                << " of the diagonal from the origin's, "
                << "volume kept to " << kept.cwiseAbs().maxCoeff() << "\n";
    }
  }
}

TEST(FarFromTheOrigin, TheGlobalVolumeSolvesToTheShapeAtTheOrigin) {
  expect_the_same_shape_far_away(test::capsule_scene({0.5, 0.6, 0.0}), {}, "global volume");
}

TEST(FarFromTheOrigin, VolumePartsSolveToTheShapeAtTheOrigin) {
  const Scene s = test::capsule_scene({0.5, 0.6, 0.0});
  expect_the_same_shape_far_away(s, test::capsule_thirds(s.mesh), "three parts");
}

TEST(FarFromTheOrigin, AnOpenMeshSolvesToTheShapeAtTheOrigin) {
  expect_the_same_shape_far_away(test::open_capsule_scene(), {}, "open capsule");
}

}  // namespace
}  // namespace sd
