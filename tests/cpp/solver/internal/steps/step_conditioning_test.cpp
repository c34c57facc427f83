// Condition numbers of the step's normal matrix: Lanczos extremes against a dense eigensolver (full space), the
// orthonormal-basis value against an explicit orthonormal basis, and Cauchy interlacing (subspace <= full).
#include "core/solver/internal/steps/step_conditioning.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "core/solver/internal/steps/full_space_step.h"
#include "core/basis/mean_value_coordinates.h"
#include "solver_fixtures.h"

namespace sd {
namespace {

struct Problem {
  test::Scene scene = test::capsule_scene({0.2, -0.5, 0.1});
  DeformationEnergy energy{scene.mesh.V, scene.mesh.F};
  BasisMatrix W = mean_value_coordinates(scene.mesh.V, scene.cage);
  Problem() {
    energy.set_handles(test::flat_handles(scene));
    energy.set_targets(scene.targets);
  }
};

TEST(StepConditioning, FullSpaceExtremesMatchADenseEigensolver) {
  Problem p;
  const Vertices X = p.scene.mesh.V * 1.01;
  const StepConditioning c = full_space_conditioning(p.energy, X);
  const FullSpaceStep full(p.energy);
  const Eigen::MatrixXd H = Eigen::MatrixXd(full.normal_matrix(p.energy.jacobian(X)));
  const Eigen::VectorXd values =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H, Eigen::EigenvaluesOnly).eigenvalues();
  EXPECT_NEAR(c.largest, values.maxCoeff(), 1e-8 * values.maxCoeff());
  EXPECT_NEAR(c.smallest, values.minCoeff(), 1e-6 * values.minCoeff());
  EXPECT_NEAR(c.condition, values.maxCoeff() / values.minCoeff(), 1e-6 * c.condition);
}

TEST(StepConditioning, OrthonormalBasisValueIsThatOfAnExplicitOrthonormalBasisAndInterlaces) {
  Problem p;
  const Vertices X = p.scene.mesh.V;
  const StepConditioning raw = subspace_conditioning(p.energy, p.W, X, false);
  const StepConditioning orthonormal = subspace_conditioning(p.energy, p.W, X, true);
  // The same operator in Q (an orthonormal basis of span W) as a "weight matrix".
  const Eigen::MatrixXd Wd = p.W.to_dense();
  const Eigen::MatrixXd Q =
      Eigen::HouseholderQR<Eigen::MatrixXd>(Wd).householderQ() * Eigen::MatrixXd::Identity(Wd.rows(), Wd.cols());
  BasisMatrix Wq(static_cast<int>(Q.rows()), static_cast<int>(Q.cols()), false);
  for (int i = 0; i < Q.rows(); ++i) Wq.set_row(i, Q.row(i));
  const StepConditioning explicit_q = subspace_conditioning(p.energy, Wq, X, false);
  EXPECT_NEAR(orthonormal.condition, explicit_q.condition, 1e-6 * explicit_q.condition);
  const StepConditioning full = full_space_conditioning(p.energy, X);
  EXPECT_LE(orthonormal.condition, full.condition * (1 + 1e-8)) << "Cauchy interlacing";
  EXPECT_GE(orthonormal.smallest, full.smallest * (1 - 1e-8));
  EXPECT_LE(orthonormal.largest, full.largest * (1 + 1e-8));
  std::cout << "[          ] kappa: full space " << full.condition << ", cage subspace " << raw.condition
            << " (in an orthonormal basis of it " << orthonormal.condition << ")\n";
}

}  // namespace
}  // namespace sd
