// The reduced integration of the subspace problem (reduced_subspace.h): derivatives against finite differences,
// the exact sum when every vertex is a sample, and the properties of its solves (rest pose, volume, merit, the
// shape against the full integration's).
#include "core/solver/internal/reduced/reduced_subspace.h"

#include <gtest/gtest.h>

#include <iostream>

#include "core/mesh/examples.h"
#include "core/mesh/volume.h"
#include "core/solver/deformer.h"
#include "core/solver/internal/reduced/rotation_clusters.h"
#include "core/solver/internal/reduced/sampled_laplacian.h"
#include "core/solver/internal/reduced/training_poses.h"
#include "core/basis/mean_value_coordinates.h"
#include "reduced_scenes.h"
#include "solver_fixtures.h"
#include "test_support.h"
#include "tools/drag_scene.h"

namespace sd {
namespace {

using test::BarScene;
using test::with;

// The pieces below the Deformer, on the bar with the sampled term at 60 spread vertices with uneven weights (so the
// sums differ from the full ones and every weight matters), or with 40 rotation clusters.
enum class Rule { Sampled, Clusters };
struct Pieces {
  BarScene scene{Eigen::RowVector3d(0.0, -0.8, 0.3)};
  DeformationEnergy energy{scene.bar.mesh.V, scene.bar.mesh.F};
  BasisMatrix W = mean_value_coordinates(scene.bar.mesh.V, scene.bar.cage);
  SubspaceStep subspace{energy, W};
  std::vector<int> samples = farthest_point_clusters(scene.bar.mesh.V, 60).samples;
  Eigen::VectorXd weights;
  std::unique_ptr<ReducedSubspace> reduced;
  explicit Pieces(Rule rule = Rule::Sampled) {
    scene.hold(energy);
    subspace.refactor(energy);
    std::sort(samples.begin(), samples.end());
    PortableRandom random(7);
    weights.resize(static_cast<Eigen::Index>(samples.size()));
    for (Eigen::Index s = 0; s < weights.size(); ++s) weights[s] = random.uniform(40.0, 120.0);
    std::unique_ptr<ReducedLaplacianTerm> term;
    if (rule == Rule::Sampled) term = std::make_unique<SampledLaplacian>(energy, W, scene.bar.cage.V, samples, weights);
    else
      term = std::make_unique<RotationClusters>(energy, W, scene.bar.cage.V, subspace.laplacian_gram(),
                                                surface_clusters(scene.bar.mesh.V, energy.coordinates(), 40));
    reduced = std::make_unique<ReducedSubspace>(energy, W, scene.bar.cage.V, subspace, std::move(term));
  }
  Vertices map(const Eigen::MatrixXd& U) const {
    Eigen::MatrixXd image;
    W.multiply(U - scene.bar.cage.V, image);
    return scene.bar.mesh.V + image;
  }
  double energy_at(const Eigen::MatrixXd& U) const { return reduced->evaluate(map(U), U).energy; }
  // Central differences of energy_at against the gradient g at U (the largest difference).
  double gradient_error(const Eigen::MatrixXd& U, const Eigen::MatrixXd& g) const {
    return test::gradient_error(U, g, [this](const Eigen::MatrixXd& V) { return energy_at(V); });
  }
  // f = [sqrt(w_s) r_s; weighted handle residuals], flattened.
  Eigen::VectorXd residual_at(const Eigen::MatrixXd& U) const {
    const EnergyEvaluation e = reduced->evaluate(map(U), U);
    Eigen::MatrixXd lap = e.laplacian_residual;
    for (Eigen::Index s = 0; s < lap.rows(); ++s) lap.row(s) *= std::sqrt(weights[s]);
    Eigen::VectorXd f(lap.size() + e.position_residual.size());
    f << Eigen::Map<const Eigen::VectorXd>(Eigen::MatrixXd(lap.transpose()).data(), lap.size()),
        Eigen::Map<const Eigen::VectorXd>(Eigen::MatrixXd(e.position_residual.transpose()).data(),
                                          e.position_residual.size());
    return f;
  }
  Eigen::MatrixXd perturbed(unsigned seed) const {
    Eigen::MatrixXd U = scene.bar.cage.V;
    PortableRandom random(seed);
    for (Eigen::Index k = 0; k < U.size(); ++k) U.data()[k] += random.uniform(-0.1, 0.1);
    return U;
  }
};

TEST(ReducedSubspace, GradientMatchesFiniteDifferences) {
  for (Rule rule : {Rule::Sampled, Rule::Clusters}) {
    Pieces p(rule);
    ASSERT_LT(p.reduced->sample_count(), 61);
    const Eigen::MatrixXd U = p.perturbed(1);
    p.reduced->linearize(U);
    const Eigen::MatrixXd g = p.reduced->gradient(p.reduced->evaluate(p.map(U), U), U);
    EXPECT_LE(p.gradient_error(U, g), 1e-6 * g.cwiseAbs().maxCoeff())
        << (rule == Rule::Sampled ? "sampled" : "clusters");
  }
}

// The handle term's gradient is remade per group as targets change (a drag moves one group): after the moving
// group's targets change, then the weight, it is still the gradient of the energy at the new targets.
TEST(ReducedSubspace, HandleGradientFollowsEachChangeOfTheTargets) {
  Pieces p(Rule::Clusters);
  const Eigen::MatrixXd U = p.perturbed(2);
  const auto check = [&](const char* what) {
    p.reduced->linearize(U);
    const Eigen::MatrixXd g = p.reduced->gradient(p.reduced->evaluate(p.map(U), U), U);
    EXPECT_LE(p.gradient_error(U, g), 1e-6 * g.cwiseAbs().maxCoeff()) << what;
  };
  check("first targets");
  Vertices moved = p.scene.targets;
  const Eigen::Index fixed_rows = static_cast<Eigen::Index>(p.scene.groups[0].size());
  for (Eigen::Index r = fixed_rows; r < moved.rows(); ++r) moved.row(r) += Eigen::RowVector3d(0.05, -0.2, 0.1);
  p.energy.set_targets(moved);
  check("the moving group's targets changed");
  moved.row(0) += Eigen::RowVector3d(0.0, 0.01, 0.0);  // and one of the fixed group's
  p.energy.set_targets(moved);
  check("a fixed group's target changed");
  p.energy.set_position_weight(2.0);
  p.subspace.refactor(p.energy);
  check("the position weight changed");
}

// The volume constraints' c (volume_directions): a step of a drag (new targets) where the mesh's volume gradient
// turned by less than kLaggedTilt since the last step uses the last step's c, so it differs from a fresh solver's
// step there and says it is lagged; at the same targets, or after a larger turn, it makes c anew and is the fresh
// solver's step bit for bit. No L-BFGS memory and the constant preconditioner: nothing else carries over from one
// step to the next.
TEST(ReducedSubspace, ADragStepKeepsTheVolumesGradientOnlyWhileTheMeshMovesLittle) {
  SolverOptions options;
  options.cg_memory = 0;
  options.preconditioner = Preconditioner::Constant;
  struct Case {
    const char* name;
    bool new_targets;
    double move;  // of the diagonal, each cage coordinate at most
    bool kept;
  };
  for (const Case c :
       {Case{"a drag frame, a small move", true, 8e-3, true}, Case{"the same targets", false, 8e-3, false},
        Case{"a drag frame, a larger move", true, 1.2e-2, false}}) {
    SCOPED_TRACE(c.name);
    Pieces dragged(Rule::Clusters), fresh(Rule::Clusters);
    const double diagonal = dragged.energy.rest_diagonal();
    const Eigen::MatrixXd U1 = dragged.perturbed(3);
    Vertices pulled = dragged.scene.targets;
    pulled.bottomRows(1) += Eigen::RowVector3d(0.0, -0.01, 0.0);
    Eigen::MatrixXd U2 = U1;
    PortableRandom random(5);
    for (Eigen::Index k = 0; k < U2.size(); ++k) U2.data()[k] += c.move * diagonal * random.uniform(-1.0, 1.0);
    const Vertices X1 = dragged.map(U1), X2 = dragged.map(U2);
    const Eigen::MatrixXd G1 = dragged.energy.constraint_gradients(X1), G2 = dragged.energy.constraint_gradients(X2);
    const double tilt = (G2 - G1).norm() / G1.norm();
    std::cout << "[          ] " << c.name << ": the volume gradient turned by " << tilt << "\n";
    EXPECT_EQ(tilt <= ReducedSubspace::kLaggedTilt, c.kept || !c.new_targets);

    dragged.reduced->step(dragged.reduced->evaluate(X1, U1), X1, U1, options);
    if (c.new_targets) {
      dragged.energy.set_targets(pulled);
      fresh.energy.set_targets(pulled);
    }
    const ConstrainedStep step = dragged.reduced->step(dragged.reduced->evaluate(X2, U2), X2, U2, options);
    const ConstrainedStep reference = fresh.reduced->step(fresh.reduced->evaluate(X2, U2), X2, U2, options);
    ASSERT_LT(reference.slope, 0.0);
    EXPECT_LT(step.slope, 0.0);
    const double difference = (step.du - reference.du).norm() / reference.du.norm();
    EXPECT_EQ(step.lagged, c.kept);
    if (c.kept) {
      EXPECT_GT(difference, 0.0) << "the kept c";
      EXPECT_LT(difference, 0.05) << "a small move tilts c a little";
      EXPECT_LT(step.passes, reference.passes) << "no transposed pass";
    } else {
      EXPECT_EQ(difference, 0.0) << "c made anew";
    }
  }
}

// The dense Gauss-Newton matrix is J^T J for the Jacobian J of the sampled residual by central differences, and
// the matrix-free product applies it.
TEST(ReducedSubspace, GaussNewtonMatrixIsJacobianTransposeJacobian) {
  Pieces p;
  const Eigen::MatrixXd U = p.perturbed(2);
  p.reduced->linearize(U);
  const Eigen::Index m = U.rows();
  const Eigen::MatrixXd J = test::central_differences(U, [&](const Eigen::MatrixXd& V) { return p.residual_at(V); });
  Eigen::MatrixXd expected = J.transpose() * J;
  const CageRegularization& reg = p.subspace.regularization();
  for (int a = 0; a < 3 && reg.active(); ++a) expected.block(a * m, a * m, m, m) += reg.eps() * reg.penalty();
  const Eigen::MatrixXd A = p.reduced->dense_matrix();
  EXPECT_LE((A - expected).cwiseAbs().maxCoeff(), 1e-6 * expected.cwiseAbs().maxCoeff());
  const Eigen::MatrixXd V = p.perturbed(3) - p.scene.bar.cage.V;
  const Eigen::MatrixXd AV = p.reduced->product(V);
  const Eigen::VectorXd flat_v = Eigen::Map<const Eigen::VectorXd>(V.data(), V.size());
  const Eigen::VectorXd dense = A * flat_v;
  EXPECT_LE((Eigen::Map<const Eigen::VectorXd>(AV.data(), AV.size()) - dense).norm(), 1e-10 * dense.norm());
}

// A mesh with no more vertices than samples integrates exactly: the reduced solve is the full subspace solve.
TEST(ReducedSubspace, EveryVertexASampleGivesTheFullSubspacesMinimiser) {
  const test::Scene s = test::capsule_scene({0.2, -0.6, 0.1});
  ASSERT_LE(s.mesh.V.rows(), 800);  // the rule sums every vertex up to max(800, 2m)
  for (JacobianMode mode : {JacobianMode::Fast, JacobianMode::Exact}) {
    Deformer full(s.mesh, s.cage), reduced(s.mesh, s.cage);
    full.set_options(with(Integration::Full, mode));
    reduced.set_options(with(Integration::Reduced, mode));
    for (Deformer* d : {&full, &reduced}) {
      d->set_handles(s.groups);
      d->set_targets(s.targets);
      ASSERT_TRUE(d->solve().converged);
    }
    EXPECT_EQ(reduced.reduced_integration().samples, s.mesh.V.rows());
    EXPECT_LE((full.positions() - reduced.positions()).rowwise().norm().maxCoeff(),
              1e-6 * bounding_box_diagonal(s.mesh.V));
  }
}

// A drag of the bar with reduced integration, one iteration per frame: most frames keep the volume's c (one pass
// over W instead of two), and every frame keeps the volume and lowers the merit. After the release, the app's loop
// (the same targets sent again with each step) makes c at every iteration and settles where a solve does.
TEST(ReducedSubspace, ADragKeepsTheVolumesGradientAndSettlesWhereASolveDoes) {
  const BarScene rest(Eigen::RowVector3d::Zero()), bent(Eigen::RowVector3d(0.3, -0.9, 0.3));
  Deformer dragged(bent.bar.mesh, bent.bar.cage), solved(bent.bar.mesh, bent.bar.cage);
  for (Deformer* d : {&dragged, &solved}) {
    d->set_options(with(Integration::Reduced, JacobianMode::Fast));
    d->set_handles(bent.groups);
  }
  const int frames = 40;
  int lagged = 0;
  for (int f = 1; f <= frames; ++f) {
    const double t = static_cast<double>(f) / frames;
    dragged.set_targets((1.0 - t) * rest.targets + t * bent.targets);
    for (const IterationStats& it : dragged.step(1).iterations) {
      EXPECT_LE(std::abs(it.volume_rel_error), 1e-9) << "frame " << f;
      EXPECT_LE(it.merit, it.merit_start) << "frame " << f;
      lagged += it.passes == 1;  // a fresh c costs a transposed pass beside the forward one
    }
  }
  std::cout << "[          ] " << lagged << " of " << frames << " frames kept the volume's gradient\n";
  EXPECT_GE(lagged, frames / 4);
  StepResult r;
  for (int k = 0; k < 300 && !r.converged; ++k) {
    dragged.set_targets(bent.targets);
    r = dragged.step(1);
    // (The solve's finishing iterations with the rule's matrix cost the same two passes; the bar finishes within them.)
    for (const IterationStats& it : r.iterations) EXPECT_EQ(it.passes, 2) << "at rest c is made anew";
  }
  ASSERT_TRUE(r.converged) << r.stop_reason;
  solved.set_targets(bent.targets);
  ASSERT_TRUE(solved.solve().converged);
  const double distance =
      (dragged.positions() - solved.positions()).rowwise().norm().maxCoeff() / bounding_box_diagonal(bent.bar.mesh.V);
  std::cout << "[          ] settled " << distance << " of the diagonal from the solve\n";
  EXPECT_LE(distance, 1e-5);
}

TEST(ReducedSubspace, RestPoseIsAFixedPoint) {
  BarScene s(Eigen::RowVector3d::Zero());
  Deformer d(s.bar.mesh, s.bar.cage);
  d.set_options(with(Integration::Reduced, JacobianMode::Fast));
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  const StepResult r = d.solve();
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_LE((d.positions() - s.bar.mesh.V).rowwise().norm().maxCoeff(), 1e-10 * bounding_box_diagonal(s.bar.mesh.V));
}

// A bend of the bar and a pull of the sphere, in both modes: the volume holds to 1e-9 at every iteration, the
// merit never rises, the rule's iterations come first and the finishing ones (section 17.3) last, and the shape is
// within 2e-5 of the diagonal of the full integration's (measured 2e-6 to 7e-6; the rule alone left 6e-5 to 1e-4).
TEST(ReducedSubspace, KeepsTheVolumeLowersTheMeritAndFindsTheFullShape) {
  for (const char* name : {"bar", "sphere"}) {
    const bool bar = std::string(name) == "bar";
    const BarScene s(bar ? Eigen::RowVector3d(0.3, -0.9, 0.3) : Eigen::RowVector3d(0.3, 0.5, 0.2), name);
    const Example& model = s.bar;
    // The exact mode (a dense 3m x 3m system per iteration) on the bar only: it is the slow one.
    for (JacobianMode mode : {JacobianMode::Fast, JacobianMode::Exact}) {
      if (!bar && mode == JacobianMode::Exact) continue;
      SCOPED_TRACE(std::string(name) + (mode == JacobianMode::Fast ? " fast" : " exact"));
      Deformer full(model.mesh, model.cage), reduced(model.mesh, model.cage);
      full.set_options(with(Integration::Full, mode));
      reduced.set_options(with(Integration::Reduced, mode));
      for (Deformer* d : {&full, &reduced}) {
        d->set_handles(s.groups);
        d->set_targets(s.targets);
      }
      ASSERT_TRUE(full.solve().converged);
      const StepResult r = reduced.solve();
      ASSERT_TRUE(r.converged) << r.stop_reason;
      for (const IterationStats& it : r.iterations) {
        EXPECT_LE(std::abs(it.volume_rel_error), 1e-9);
        EXPECT_LE(it.merit, it.merit_start);
        EXPECT_EQ(it.samples, it.finishing ? 0 : reduced.reduced_integration().samples);
      }
      EXPECT_FALSE(r.iterations.front().finishing);
      EXPECT_TRUE(r.iterations.back().finishing);
      const double difference =
          (full.positions() - reduced.positions()).rowwise().norm().maxCoeff() / bounding_box_diagonal(model.mesh.V);
      std::cout << "[          ] " << name << ": reduced vs full " << difference << " of the diagonal, "
                << reduced.reduced_integration().samples << " samples, test error "
                << reduced.reduced_integration().test_error << "\n";
      EXPECT_LE(difference, 2e-5);
    }
  }
}

// Real models in their own cages (test data), the drag of bench_models: the rotation-cluster rule passes its test
// and the reduced solve, finished on every vertex (section 17.3), lies within 1e-4 of the diagonal of the full one
// (measured 4e-6 and 1e-5; the rule alone converged 1.9e-3 and 2.5e-3 off; issue 29 asked for 2e-3); or the rule says
// it is not reliable (the
// hand bones: test error 0.56), and the solve still converges, finishing with full integration's steps (to one of
// the pull's several minima, 3.7e-3 from the full solve's).
struct RealModelCase {
  const char* name;
  bool reliable;
};
class ReducedOnRealModels : public ::testing::TestWithParam<RealModelCase> {};

TEST_P(ReducedOnRealModels, FindsTheFullShapeOrSaysSo) {
  const std::string name = GetParam().name;
  SD_REQUIRE_SHARED_DATA(name + ".obj");
  SD_REQUIRE_SHARED_DATA(name + "_cage.obj");
  const Mesh mesh = test::load_shared_mesh(name + ".obj"), cage = test::load_shared_mesh(name + "_cage.obj");
  const tools::DragScene scene = tools::drag_scene(mesh);
  Deformer full(mesh, cage), reduced(mesh, cage);
  full.set_options(with(Integration::Full, JacobianMode::Fast));
  reduced.set_options(with(Integration::Reduced, JacobianMode::Fast));
  for (Deformer* d : {&full, &reduced}) {
    d->set_handles(scene.groups);
    d->set_targets(scene.targets(1.0));
  }
  reduced.prepare_reduced();
  const ReducedIntegrationInfo rule = reduced.reduced_integration();
  EXPECT_EQ(rule.rule, "clusters");
  EXPECT_EQ(rule.reliable, GetParam().reliable) << "test error " << rule.test_error;
  ASSERT_TRUE(full.solve().converged);
  const StepResult r = reduced.solve();
  ASSERT_TRUE(r.converged) << r.stop_reason;
  EXPECT_TRUE(r.iterations.back().finishing);
  for (const IterationStats& it : r.iterations) EXPECT_LE(std::abs(it.volume_rel_error), 1e-9);
  const double difference =
      (full.positions() - reduced.positions()).rowwise().norm().maxCoeff() / bounding_box_diagonal(mesh.V);
  std::cout << "[          ] " << name << ": reduced vs full " << difference << " of the diagonal, test error "
            << rule.test_error << "\n";
  if (GetParam().reliable) EXPECT_LE(difference, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(SharedData, ReducedOnRealModels,
                         ::testing::Values(RealModelCase{"gargoyle", true}, RealModelCase{"moomoo", true},
                                           RealModelCase{"handbones", false}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace sd
