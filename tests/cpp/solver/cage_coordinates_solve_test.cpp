// The solver with each cage coordinate type (mean value, positive mean value, harmonic): W is a dense
// BasisMatrix whatever the type, so every subspace mode must work unchanged: fast and exact steps, volume
// parts, the cage regularisation on and off, reduced integration, both weightings, the cage quality.
#include <gtest/gtest.h>

#include <cstdio>

#include "core/parts/part_volume.h"
#include "core/solver/deformer.h"
#include "test_support.h"
#include "basis/cage_fixtures.h"

namespace sd {
namespace {

// The C of the bent bar with its lower end fixed and its upper end pulled outwards: a drag across the cage's
// concavity, where mean value weights are negative.
struct CScene {
  test::BentBar bar = test::bent_bar();
  std::vector<std::vector<int>> groups;
  Vertices rest_targets, targets;
};

CScene c_scene() {
  CScene s;
  const Mesh straight = make_capsule(4.0, 0.5, 6, 24, 24);  // bent_bar's capsule before bending: same vertex order
  std::vector<int> fixed, moved;
  for (int i = 0; i < straight.V.rows(); ++i) {
    if (straight.V(i, 0) < -2.2) fixed.push_back(i);
    if (straight.V(i, 0) > 2.2) moved.push_back(i);
  }
  s.groups = {fixed, moved};
  s.rest_targets.resize(fixed.size() + moved.size(), 3);
  s.targets.resize(fixed.size() + moved.size(), 3);
  int r = 0;
  for (int v : fixed) s.rest_targets.row(r) = s.targets.row(r) = s.bar.mesh.V.row(v), ++r;
  for (int v : moved) {
    s.rest_targets.row(r) = s.bar.mesh.V.row(v);
    s.targets.row(r++) = s.bar.mesh.V.row(v) + Eigen::RowVector3d(0.5, 0.4, 0.0);
  }
  return s;
}

BasisOptions basis_for(CoordinateType type) {
  BasisOptions basis;
  basis.coordinates.type = type;
  basis.coordinates.positive.resolution = 8;
  basis.coordinates.harmonic.resolution = 16;
  return basis;
}

SolverOptions subspace(JacobianMode mode, double regularization = 1e-3) {
  SolverOptions o;
  o.method = Method::Subspace;
  o.jacobian = mode;
  o.max_iterations = 200;
  o.cage_regularization = regularization;
  return o;
}

// Two volume parts: the two halves of the C (by the triangle's centroid angle, i.e. its x before bending).
std::vector<int> halves(const Mesh& straight) {
  std::vector<int> parts(static_cast<size_t>(straight.F.rows()));
  for (int f = 0; f < straight.F.rows(); ++f)
    parts[f] =
        straight.V(straight.F(f, 0), 0) + straight.V(straight.F(f, 1), 0) + straight.V(straight.F(f, 2), 0) < 0 ? 0 : 1;
  return parts;
}

class EachCoordinateType : public ::testing::TestWithParam<CoordinateType> {};

TEST_P(EachCoordinateType, RestPoseIsAFixedPoint) {
  const CScene s = c_scene();
  Deformer d(s.bar.mesh, s.bar.cage, basis_for(GetParam()));
  EXPECT_EQ(d.coordinates_report().type, GetParam());
  d.set_options(subspace(JacobianMode::Fast));
  d.set_handles(s.groups);
  d.set_targets(s.rest_targets);
  d.step(3);
  // X = X0 + W (P - P0) keeps the rest pose exactly whatever W's linear precision.
  EXPECT_LE((d.positions() - s.bar.mesh.V).cwiseAbs().maxCoeff(), 1e-12);
}

TEST_P(EachCoordinateType, FastAndExactStepsReachTheSameShapeKeepingTheVolume) {
  const CScene s = c_scene();
  const double diagonal = bounding_box_diagonal(s.bar.mesh.V);
  Vertices shapes[2];
  int k = 0;
  for (JacobianMode mode : {JacobianMode::Exact, JacobianMode::Fast}) {
    Deformer d(s.bar.mesh, s.bar.cage, basis_for(GetParam()));
    d.set_options(subspace(mode));
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    const StepResult r = d.solve();
    ASSERT_FALSE(r.iterations.empty());
    EXPECT_TRUE(r.converged) << stop_code_name(r.stop);
    EXPECT_LE(std::abs(r.iterations.back().volume_rel_error), 1e-8);
    EXPECT_LT(r.iterations.back().merit, r.iterations.front().merit_start);
    shapes[k++] = d.positions();
    std::printf("[ solve    ] %s %s: %d iterations, energy %.4g, cage regularisation %.3g\n",
                coordinate_type_name(GetParam()), mode == JacobianMode::Exact ? "exact" : "fast",
                int(r.iterations.size()), r.iterations.back().energy, r.iterations.back().regularization_energy);
  }
  EXPECT_LE((shapes[0] - shapes[1]).rowwise().norm().maxCoeff(), 2e-3 * diagonal);
}

TEST_P(EachCoordinateType, VolumePartsAndTheCageRegularisation) {
  const CScene s = c_scene();
  const std::vector<int> parts = halves(make_capsule(4.0, 0.5, 6, 24, 24));
  for (double regularization : {0.0, 1e-3}) {
    Deformer d(s.bar.mesh, s.bar.cage, basis_for(GetParam()));
    d.set_options(subspace(JacobianMode::Fast, regularization));
    d.set_volume_parts(parts);
    d.set_handles(s.groups);
    d.set_targets(s.targets);
    const StepResult r = d.solve();
    EXPECT_TRUE(r.converged) << stop_code_name(r.stop) << " regularisation " << regularization;
    ASSERT_EQ(r.iterations.back().part_volume_change.size(), 2u);
    for (double change : r.iterations.back().part_volume_change) EXPECT_LE(std::abs(change), 1e-8);
    if (regularization == 0) EXPECT_EQ(r.iterations.back().regularization_energy, 0.0);
    EXPECT_TRUE(d.cage_positions().allFinite());
  }
}

// Reduced integration samples rows of W like any other: the volume holds and the shape is the full
// integration's within 5e-3 of the diagonal (its bound on the bar and sphere, reduced_subspace_test.cpp). With
// either weighting: the uniform one (every vertex and handle alike) changes the terms and the fit, not W.
TEST_P(EachCoordinateType, ReducedIntegrationFindsTheFullShapeWithEitherWeighting) {
  const CScene s = c_scene();
  const double diagonal = bounding_box_diagonal(s.bar.mesh.V);
  for (EnergyWeighting weighting : {EnergyWeighting::Area, EnergyWeighting::Uniform}) {
    const char* weighting_name = weighting == EnergyWeighting::Area ? "area" : "uniform";
    Vertices shapes[2];
    int k = 0;
    for (Integration integration : {Integration::Full, Integration::Reduced}) {
      Deformer d(s.bar.mesh, s.bar.cage, basis_for(GetParam()));
      SolverOptions o = subspace(JacobianMode::Fast);
      o.integration = integration;
      o.weighting = weighting;
      d.set_options(o);
      d.set_handles(s.groups);
      d.set_targets(s.targets);
      const StepResult r = d.solve();
      ASSERT_FALSE(r.iterations.empty());
      EXPECT_TRUE(r.converged) << stop_code_name(r.stop) << ", " << weighting_name;
      EXPECT_LE(std::abs(r.iterations.back().volume_rel_error), 1e-8);
      EXPECT_LT(r.iterations.back().merit, r.iterations.front().merit_start);
      if (integration == Integration::Reduced) EXPECT_GT(d.reduced_integration().samples, 0);
      shapes[k++] = d.positions();
    }
    const double difference = (shapes[0] - shapes[1]).rowwise().norm().maxCoeff() / diagonal;
    std::printf("[ reduced  ] %s, %s weighting: reduced vs full %.3g of the diagonal\n",
                coordinate_type_name(GetParam()), weighting_name, difference);
    EXPECT_LE(difference, 5e-3);
  }
}

TEST_P(EachCoordinateType, CageQualityReadsW) {
  const CScene s = c_scene();
  Deformer d(s.bar.mesh, s.bar.cage, basis_for(GetParam()));
  const CageQuality q = d.cage_quality();
  EXPECT_EQ(q.cage_vertices, s.bar.cage.V.rows());
  EXPECT_GT(q.min_column_max, 0.0);
  EXPECT_TRUE(std::isfinite(q.influence_ratio));
  EXPECT_GT(q.volume_ratio, 1.0);
  std::printf("[ quality  ] %s: weak vertices %d, influence ratio %.2g, warnings %zu\n",
              coordinate_type_name(GetParam()), q.weak_vertices, q.influence_ratio, q.warnings.size());
}

INSTANTIATE_TEST_SUITE_P(CageCoordinates, EachCoordinateType, ::testing::ValuesIn(all_coordinate_types()),
                         [](const ::testing::TestParamInfo<CoordinateType>& info) {
                           return std::string(coordinate_type_name(info.param));
                         });

// Binding errors of the other types reach the session's caller as for mean value coordinates.
TEST(CageCoordinatesSession, RefusesAHarmonicGridOverTheBudget) {
  const CScene s = c_scene();
  BasisOptions basis = basis_for(CoordinateType::Harmonic);
  basis.coordinates.harmonic.resolution = 1024;
  basis.cage.memory_budget_bytes = 50'000'000;
  test::expect_error([&] { Deformer d(s.bar.mesh, s.bar.cage, basis); }, "over the memory budget",
                     ErrorCode::MemoryBudget);
}

}  // namespace
}  // namespace sd
