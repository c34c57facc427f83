// The bones' soft straightness term (option straightnessWeight, docs/method.md section 5.4): each bone's seven samples
// pulled towards their places on the segment between its deformed joints. Checked: its gradient and its Gauss-Newton
// product against central differences, the same term in every step solver's own form (the subspace's m x 7B rows,
// its H and exact Jacobian, the full space's Woodbury solve), the rest pose as a fixed point, the arm straighter in
// every method and integration with the lengths and the volume still exact, the same pose whichever order the session
// is told the skeleton and the weight in, and the same pose at two mesh resolutions.
#include <gtest/gtest.h>

#include <cmath>

#include "core/basis/mean_value_coordinates.h"
#include "core/mesh/shapes.h"
#include "core/mesh/volume.h"
#include "core/solver/deformer.h"
#include "core/solver/internal/constraints/skeleton_constraints.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/steps/full_space_step.h"
#include "core/solver/internal/steps/subspace_step.h"
#include "skeleton/arm_scene.h"
#include "test_support.h"

namespace sd {
namespace {

using test::Arm;
using test::fixed_directions;
using test::method;
using test::wobbled;

constexpr double kWeight = 10.0;

double dot(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a.array() * b.array()).sum(); }

struct Posed {
  SkeletonReport bones;
  StepResult result;
  double volume_error = 1;
  Vertices X;
};

Posed pose(const Arm& arm, SolverOptions options, double weight) {
  options.straightness_weight = weight;
  Deformer d(arm.mesh, arm.cage);
  d.set_options(options);
  d.set_handles(arm.groups);
  d.set_skeleton(arm.skeleton);
  d.set_targets(arm.targets);
  Posed out;
  out.result = d.solve();
  out.bones = *d.skeleton_report();
  out.volume_error = std::abs(signed_volume(d.positions(), arm.mesh.F) / d.rest_volume() - 1.0);
  out.X = d.positions();
  return out;
}

// E_s = w^2 / 2 sum |offset|^2 is quadratic in X: its gradient (part of J_f^T f) must match central differences of
// the energy along any direction, and its Gauss-Newton product (part of J_f^T J_f) the differences of that gradient.
TEST(BoneStraightness, GradientAndProductMatchFiniteDifferences) {
  const Arm arm;
  DeformationEnergy energy(arm.mesh.V, arm.mesh.F);
  energy.set_skeleton(std::make_unique<SkeletonConstraints>(arm.skeleton, arm.mesh));
  const Vertices X = wobbled(arm.mesh, 0.1), V = fixed_directions(X.rows(), 3);
  const auto term_gradient = [&](const Vertices& Y, double w) {
    energy.set_straightness_weight(w);
    const EnergyEvaluation e = energy.evaluate(Y);
    return Eigen::MatrixXd(energy.jacobian(Y).gradient(e));
  };
  const auto energy_at = [&](const Vertices& Y) { return energy.evaluate(Y).energy; };
  energy.set_straightness_weight(kWeight);
  const EnergyEvaluation e = energy.evaluate(X);
  ASSERT_GT(e.straightness_energy, 1e-4) << "the wobble bends the bones: not a trivial comparison";
  const double h = 1e-6;
  const double slope = (energy_at(X + h * V) - energy_at(X - h * V)) / (2 * h);
  EXPECT_NEAR(dot(energy.jacobian(X).gradient(e), V), slope, 1e-6 * std::abs(slope)) << "the whole energy's gradient";
  // The term alone: the gradient with the weight less the gradient without it, and its product likewise.
  const Eigen::MatrixXd term = term_gradient(X, kWeight) - term_gradient(X, 0.0);
  energy.set_straightness_weight(0.0);
  const double base = (energy_at(X + h * V) - energy_at(X - h * V)) / (2 * h);
  EXPECT_NEAR(dot(term, V), slope - base, 1e-6 * std::abs(slope - base));
  const Eigen::MatrixXd without = energy.jacobian(X).normal_product(V);
  energy.set_straightness_weight(kWeight);
  const Eigen::MatrixXd product = energy.jacobian(X).normal_product(V) - without;
  const Eigen::MatrixXd fd = (term_gradient(X + h * V, kWeight) - term_gradient(X + h * V, 0.0) -
                              term_gradient(X - h * V, kWeight) + term_gradient(X - h * V, 0.0)) /
                             (2 * h);
  EXPECT_LE((product - fd).norm(), 1e-6 * fd.norm());
  EXPECT_GT(fd.norm(), 1e-3) << "not a trivial comparison";
}

// The arm's energy with its handles, skeleton and the weight w.
struct ArmEnergy {
  DeformationEnergy energy;
  ArmEnergy(const Arm& arm, double w) : energy(arm.mesh.V, arm.mesh.F) {
    std::vector<int> handles, sizes;
    for (const std::vector<int>& g : arm.groups) {
      handles.insert(handles.end(), g.begin(), g.end());
      sizes.push_back(static_cast<int>(g.size()));
    }
    energy.set_handles(handles, sizes);
    energy.set_targets(arm.targets);
    energy.set_skeleton(std::make_unique<SkeletonConstraints>(arm.skeleton, arm.mesh));
    energy.set_straightness_weight(w);
  }
};

// Each step solver applies the term in a form of its own; each must be w_s^2 (P O)(P O)^T seen through its unknowns.
TEST(BoneStraightness, EveryStepSolverSeesTheSameTerm) {
  const Arm arm;
  const BasisMatrix W = mean_value_coordinates(arm.mesh.V, arm.cage);
  const Eigen::MatrixXd Wd = W.to_dense();
  ArmEnergy with(arm, kWeight), without(arm, 0.0);
  SubspaceStep sub_with(with.energy, W), sub_without(without.energy, W);
  for (SubspaceStep* sub : {&sub_with, &sub_without}) sub->set_rest_unknowns(arm.cage.V);
  sub_with.refactor(with.energy);
  sub_without.refactor(without.energy);
  // The term's matrix in the subspace, formed densely from its rows on the mesh.
  const Eigen::MatrixXd R = Wd.transpose() * with.energy.skeleton()->offset_rows();
  const Eigen::MatrixXd term = kWeight * kWeight * R * R.transpose();
  EXPECT_LE((sub_with.handle_gram() - sub_without.handle_gram() - term).norm(), 1e-10 * term.norm()) << "H";
  // The product through the m x 7B rows, against the mesh's #V x 7B ones and against the exact step's dense Jacobian.
  const Eigen::MatrixXd U = arm.cage.V + 0.05 * fixed_directions(arm.cage.V.rows(), 3);
  const Vertices X = arm.mesh.V + Wd * (U - arm.cage.V);
  const EnergyJacobian J = with.energy.jacobian(X);
  const Eigen::MatrixXd V = fixed_directions(arm.cage.V.rows(), 6);
  Eigen::MatrixXd image;
  const Eigen::MatrixXd AV = sub_with.product(J, V, image);
  EXPECT_LE((AV - Wd.transpose() * J.normal_product(Wd * V)).norm(), 1e-10 * AV.norm()) << "product";
  const Eigen::MatrixXd JW = sub_with.dense_jacobian(J);
  const Eigen::Index m = W.cols();
  const Eigen::MatrixXd v = V.leftCols(3).reshaped(3 * m, 1);
  EXPECT_LE((JW.transpose() * (JW * v) - AV.leftCols(3).reshaped(3 * m, 1)).norm(), 1e-10 * AV.norm()) << "exact";
  // The full space: its exact step (the sparse factor and the term by Woodbury) and its fast one (products on the
  // mesh) solve the same equations.
  FullSpaceStep full(with.energy);
  full.refactor(with.energy);
  const EnergyEvaluation e = with.energy.evaluate(X);
  SolverOptions exact = method(Method::Full, JacobianMode::Exact), fast = method(Method::Full);
  fast.cg_tolerance = 1e-12;
  fast.cg_max_iterations = 100000;
  const ConstrainedStep a = full.compute(J, e, X, X, exact);
  full.forget_history();  // no lengths' curvature from the first step's multipliers
  const ConstrainedStep b = full.compute(J, e, X, X, fast);
  EXPECT_LE((a.du - b.du).norm(), 1e-6 * a.du.norm()) << "full space";
  // The Woodbury solve's dense blocks (2 x 3#V x 21B doubles) within the exact mode's memory budget, or refused.
  exact.exact_memory_budget_bytes = 1e5;
  try {
    full.compute(J, e, X, X, exact);
    ADD_FAILURE() << "the exact full-space step with the straightness term ignored the memory budget";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::MemoryBudget);
    EXPECT_NE(std::string(error.what()).find("straightness"), std::string::npos) << error.what();
  }
}

TEST(BoneStraightness, TheRestPoseIsAFixedPoint) {
  const Arm arm;
  DeformationEnergy energy(arm.mesh.V, arm.mesh.F);
  energy.set_skeleton(std::make_unique<SkeletonConstraints>(arm.skeleton, arm.mesh));
  energy.set_straightness_weight(kWeight);
  EXPECT_EQ(energy.evaluate(arm.mesh.V).straightness_energy, 0.0) << "the rest offsets are subtracted exactly";
  for (const SolverOptions& o : {method(Method::Subspace), method(Method::Full)}) {
    SolverOptions options = o;
    options.straightness_weight = kWeight;
    Deformer d(arm.mesh, arm.cage);
    d.set_options(options);
    d.set_handles(arm.groups);
    d.set_skeleton(arm.skeleton);
    d.solve();
    EXPECT_LE((d.positions() - arm.mesh.V).cwiseAbs().maxCoeff(), 1e-12);
  }
}

// The term straightens the arm in every method and integration, while the lengths and the volume stay hard; the
// subspace's fast, exact and reduced steps reach one minimum (the reduced rule up to its own approximation).
TEST(BoneStraightness, StraightensTheArmInEveryMethodKeepingLengthsAndVolume) {
  const Arm arm;
  const SolverOptions cases[] = {method(Method::Subspace), method(Method::Subspace, JacobianMode::Exact),
                                 method(Method::Subspace, JacobianMode::Fast, Integration::Reduced),
                                 method(Method::Full), method(Method::Full, JacobianMode::Exact)};
  double subspace_energy = 0;
  for (const SolverOptions& o : cases) {
    const std::string name = std::string(o.method == Method::Full ? "full" : "subspace") +
                             (o.jacobian == JacobianMode::Exact ? " exact" : " fast") +
                             (o.integration == Integration::Reduced ? " reduced" : "");
    const Posed loose = pose(arm, o, 0.0), straight = pose(arm, o, kWeight);
    EXPECT_NE(straight.result.stop, StopCode::NumericalFailure) << name << ": " << straight.result.stop_reason;
    EXPECT_LE(straight.bones.max_length_error(), 1e-9) << name;
    EXPECT_LE(straight.volume_error, 1e-9) << name;
    EXPECT_LE(straight.bones.max_straightness_error(), 0.6 * loose.bones.max_straightness_error()) << name;
    const double energy = straight.result.iterations.back().energy;
    if (o.method == Method::Subspace && o.integration == Integration::Full && o.jacobian == JacobianMode::Fast)
      subspace_energy = energy;
    else if (o.method == Method::Subspace)
      EXPECT_NEAR(energy, subspace_energy, (o.integration == Integration::Reduced ? 2e-2 : 1e-5) * subspace_energy)
          << name << ": " << straight.result.stop_reason;
  }
}

// The weight set after the skeleton, or the skeleton after the weight: the same factors, the same pose; and the term
// goes with the weight set back to 0 or with the skeleton. With reduced integration H enters the gradient, so a stale
// one would move the pose, not only the steps.
TEST(BoneStraightness, TheOrderOfSkeletonAndWeightDoesNotMatter) {
  const Arm arm;
  for (const Integration integration : {Integration::Full, Integration::Reduced}) {
    const SolverOptions plain = method(Method::Subspace, JacobianMode::Fast, integration);
    SolverOptions weighted = plain;
    weighted.straightness_weight = kWeight;
    const auto session = [&](const SolverOptions& options) {
      auto d = std::make_unique<Deformer>(arm.mesh, arm.cage);
      d->set_options(options);
      d->set_handles(arm.groups);
      d->set_targets(arm.targets);
      return d;
    };
    const std::string name = integration == Integration::Full ? "full" : "reduced";
    const Posed first = pose(arm, plain, kWeight);
    std::unique_ptr<Deformer> later = session(plain);
    later->set_skeleton(arm.skeleton);
    later->set_options(weighted);
    later->solve();
    EXPECT_LE((later->positions() - first.X).cwiseAbs().maxCoeff(), 1e-8) << name << ": the weight after";
    // Back to 0, and from the rest pose (set_options of a method resets only on a method change: a twin compares).
    std::unique_ptr<Deformer> off = session(weighted), twin = session(plain);
    off->set_skeleton(arm.skeleton);
    twin->set_skeleton(arm.skeleton);
    off->set_options(plain);
    off->solve();
    twin->solve();
    EXPECT_LE((off->positions() - twin->positions()).cwiseAbs().maxCoeff(), 1e-8) << name << ": the weight back to 0";
    // The skeleton removed with the weight still set: as a session without either.
    std::unique_ptr<Deformer> removed = session(weighted), bare = session(plain);
    removed->set_skeleton(arm.skeleton);
    removed->set_skeleton(Skeleton{});
    removed->solve();
    bare->solve();
    EXPECT_LE((removed->positions() - bare->positions()).cwiseAbs().maxCoeff(), 1e-8) << name << ": no skeleton";
  }
}

// The term is made of points inside the mesh, not of its vertices: the same cage and scene at two mesh resolutions
// give nearly the same pose, as without it (docs/method.md section 5.1). The forearm is turned down by 60 degrees
// about the elbow, which leaves the arm's ends as far apart as at rest: the folding pull of the other tests
// compresses the arm, which then buckles out of its plane to one side or the other.
TEST(BoneStraightness, TheSamePoseAtTwoResolutions) {
  Arm coarse, fine(make_capsule(4.0, 0.5, 8, 32, 24));
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(-M_PI / 3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (Arm* arm : {&coarse, &fine}) {
    const Eigen::Index held = static_cast<Eigen::Index>(arm->groups[0].size());
    for (size_t k = 0; k < arm->groups[1].size(); ++k)
      arm->targets.row(held + static_cast<Eigen::Index>(k)) = arm->mesh.V.row(arm->groups[1][k]) * turn.transpose();
  }
  // A moderate weight: larger ones pull this coarse cage towards other poses (docs/experiments/skeleton.md).
  for (double w : {0.0, 3.0}) {
    const Posed a = pose(coarse, method(Method::Subspace), w), b = pose(fine, method(Method::Subspace), w);
    EXPECT_TRUE(a.result.converged && b.result.converged) << "weight " << w;
    EXPECT_LE((a.bones.joints - b.bones.joints).cwiseAbs().maxCoeff(), 2.5e-2) << "weight " << w << ", of 6.2";
    EXPECT_NEAR(a.bones.max_straightness_error(), b.bones.max_straightness_error(), 2e-3) << "weight " << w;
  }
}

}  // namespace
}  // namespace sd
