// Volume kept per part through the Deformer: one part is the global constraint to the bit, K parts each keep
// their volume (where the global constraint alone lets a part change by percents) in every mode and basis, the
// statistics report each part, and bad partitions are refused.
#include <gtest/gtest.h>

#include <cmath>

#include "core/parallel/thread_pool.h"
#include "core/parts/part_volume.h"
#include "core/solver/deformer.h"
#include "solver_fixtures.h"
#include "test_support.h"

namespace sd {
namespace {

using test::Scene;

using test::capsule_thirds;
using test::Combo;
using test::kCombos;

SolverOptions options_for(const Combo& c) {
  SolverOptions o;
  o.method = c.method;
  o.jacobian = c.mode;
  o.max_iterations = 200;
  return o;
}

// The right end pulled away and down: with one global constraint the middle thins while the ends keep or
// gain volume.
Scene stretch() { return test::capsule_scene({1.2, -0.6, 0.0}); }

TEST(VolumeParts, OnePartGivesTheGlobalIteratesToTheBit) {
  const Scene s = stretch();
  for (const Combo& c : kCombos) {
    Deformer global(s.mesh, s.cage), one(s.mesh, s.cage);
    one.set_volume_parts(std::vector<int>(s.mesh.F.rows(), 0));
    for (Deformer* d : {&global, &one}) {
      d->set_options(options_for(c));
      d->set_handles(s.groups);
      d->set_targets(s.targets);
    }
    const StepResult a = global.solve(), b = one.solve();
    ASSERT_EQ(a.iterations.size(), b.iterations.size()) << c.name;
    for (size_t k = 0; k < a.iterations.size(); ++k) {
      EXPECT_EQ(a.iterations[k].merit, b.iterations[k].merit) << c.name << " iteration " << k;
      EXPECT_EQ(a.iterations[k].lambda, b.iterations[k].lambda) << c.name << " iteration " << k;
    }
    EXPECT_TRUE(global.positions() == one.positions()) << c.name;
    ASSERT_EQ(b.iterations.back().part_volume_change.size(), 1u);
    EXPECT_TRUE(a.iterations.back().part_volume_change.empty()) << "no per-part stats without parts";
  }
}

TEST(VolumeParts, EachPartKeepsItsVolumeWhereTheGlobalConstraintLetsItChange) {
  const Scene s = stretch();
  const std::vector<int> parts = capsule_thirds(s.mesh);
  for (const Combo& c : kCombos) {
    Deformer d(s.mesh, s.cage);
    d.set_options(options_for(c));
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    const StepResult global = d.solve();
    ASSERT_TRUE(global.converged) << c.name << ": " << global.stop_reason;
    const PartVolumes measure(s.mesh.F, static_cast<int>(s.mesh.V.rows()), parts);
    const VolumeReference o = volume_reference(s.mesh.V, s.mesh.F);
    const Eigen::VectorXd rest = measure.evaluate(s.mesh.V, o);
    const Eigen::VectorXd change = (measure.evaluate(d.positions(), o) - rest).cwiseQuotient(rest);
    EXPECT_GE(change.cwiseAbs().maxCoeff(), 0.02) << c.name << ": the global constraint alone lets a part change";
    d.set_volume_parts(parts);
    d.reset();
    const StepResult kept = d.solve();
    ASSERT_TRUE(kept.converged) << c.name << ": " << kept.stop_reason;
    const IterationStats& last = kept.iterations.back();
    ASSERT_EQ(last.part_volume_change.size(), 3u);
    ASSERT_EQ(last.part_lambda.size(), 3u);
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(last.part_volume_change[k]), 1e-8) << c.name << " part " << k;
    EXPECT_LE((d.part_volumes() - rest).cwiseQuotient(rest).cwiseAbs().maxCoeff(), 1e-8) << c.name;
    EXPECT_LE(std::abs(last.volume_rel_error), 1e-8) << c.name << ": so is the total";
    for (size_t k = 1; k < kept.iterations.size(); ++k)
      EXPECT_LE(kept.iterations[k].merit, kept.iterations[k - 1].merit * (1 + 1e-12)) << c.name << " iteration " << k;
    std::cout << "[          ] " << c.name << ": part changes with the global constraint " << change.transpose()
              << "; per part: " << kept.iterations.size() << " iterations, energy " << last.energy << " (global "
              << global.iterations.back().energy << ")\n";
  }
}

TEST(VolumeParts, WorkWithTheSpectralBasis) {
  const Scene s = stretch();
  BasisOptions basis;
  basis.kind = BasisKind::Spectral;
  basis.spectral.modes = 16;
  Deformer d(s.mesh, Mesh{Vertices(0, 3), Faces(0, 3)}, basis);
  d.set_volume_parts(capsule_thirds(s.mesh));
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  for (JacobianMode mode : {JacobianMode::Exact, JacobianMode::Fast}) {
    SolverOptions o;
    o.jacobian = mode;
    d.set_options(o);
    d.reset();
    const StepResult r = d.solve();
    ASSERT_TRUE(r.converged) << r.stop_reason;
    for (double change : r.iterations.back().part_volume_change) EXPECT_LE(std::abs(change), 1e-8);
  }
}

// The spectral basis and the part volumes run on the pool with fixed blocks: 1, 2 and 4 threads give the same bits.
TEST(VolumeParts, WithTheSpectralBasisOneTwoAndFourThreadsGiveBitIdenticalResults) {
  const int saved = parallel::threads();
  const Scene s = test::capsule_scene({0.0, -0.7, 0.2}, 8, 60, 48, 8);  // ~4000 vertices: several blocks
  ASSERT_GT(s.mesh.V.rows(), 3000);
  const auto solve_with = [&](int threads) {
    EXPECT_EQ(parallel::set_threads(threads), threads);
    BasisOptions basis;
    basis.kind = BasisKind::Spectral;
    basis.spectral.modes = 20;
    Deformer d(s.mesh, Mesh{Vertices(0, 3), Faces(0, 3)}, basis);
    d.set_volume_parts(capsule_thirds(s.mesh));
    SolverOptions o;
    o.max_iterations = 5;
    d.set_options(o);
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    std::vector<double> record;
    for (const IterationStats& it : d.solve().iterations)
      record.insert(record.end(), {it.energy, it.part_volume_change[1]});
    const Vertices& X = d.positions();
    record.insert(record.end(), X.data(), X.data() + X.size());
    return record;
  };
  const std::vector<double> one = solve_with(1);
  for (int threads : {2, 4}) EXPECT_TRUE(one == solve_with(threads)) << threads << " threads";
  parallel::set_threads(saved);
}

TEST(VolumeParts, BadPartitionsAreRefusedAndTheSessionIsUnchanged) {
  const Scene s = stretch();
  Deformer d(s.mesh, s.cage);
  d.set_volume_parts(capsule_thirds(s.mesh));
  test::expect_error([&] { d.set_volume_parts(std::vector<int>(5, 0)); }, "5 part indices for");
  std::vector<int> gap(s.mesh.F.rows(), 0);
  gap[0] = 2;
  test::expect_error([&] { d.set_volume_parts(gap); }, "part 1 has no triangle");
  EXPECT_EQ(d.volume_parts(), capsule_thirds(s.mesh));
  EXPECT_EQ(d.rest_part_volumes().size(), 3);
  d.set_volume_parts({});
  EXPECT_TRUE(d.volume_parts().empty());
  EXPECT_EQ(d.rest_part_volumes().size(), 1);
  EXPECT_EQ(d.rest_part_volumes()[0], d.rest_volume());
}

}  // namespace
}  // namespace sd
