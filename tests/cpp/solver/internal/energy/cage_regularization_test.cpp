// The cage regularisation (docs/method.md section 6.1): the term itself (affine cage motions are free, its
// gradient and Hessian products, the filter damps only near-null directions of W^T W), and what it is for:
// the cow's cage stays together on a head pull, while the meshes of sound cages move by < 1e-4 of the
// diagonal compared with the unregularised solve.
#include "core/solver/internal/energy/cage_regularization.h"

#include <gtest/gtest.h>

#include <iostream>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <numeric>
#include <random>
#include <string>

#include "core/mesh/examples.h"
#include "core/mesh/volume.h"
#include "core/solver/deformer.h"
#include "solver_fixtures.h"
#include "test_support.h"

namespace sd {
namespace {

Eigen::MatrixXd random_matrix(int rows, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  return Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return u(rng); });
}

// G = Q diag(lambda) Q^T for a rest cage as mean value coordinates see it: the affine maps of the rest cage
// (Q's first 4 columns span 1, x0, y0, z0) move the mesh fully (lambda = 1, W reproduces them), `weak` further
// motions barely move it (lambda = 1e-9) and the others lie in [1e-3, 1].
struct Spectrum {
  Eigen::MatrixXd G, Q, rest;
  Eigen::VectorXd lambda;
};
Spectrum spectrum(int m, int weak, unsigned seed) {
  Spectrum s;
  s.rest = random_matrix(m, 3, seed);
  Eigen::MatrixXd A(m, m);
  A << Eigen::VectorXd::Ones(m), s.rest, random_matrix(m, m - 4, seed + 1);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  s.Q = qr.householderQ() * Eigen::MatrixXd::Identity(m, m);
  s.lambda.resize(m);
  s.lambda.head(4).setOnes();
  s.lambda.segment(4, weak).setConstant(1e-9);
  s.lambda.tail(m - 4 - weak) =
      Eigen::VectorXd::LinSpaced(m - 4 - weak, -3, 0).unaryExpr([](double e) { return std::pow(10.0, e); });
  s.G = s.Q * s.lambda.asDiagonal() * s.Q.transpose();
  return s;
}

TEST(CageRegularization, AffineCageMotionsCostNothing) {
  const int m = 30;
  const Spectrum s = spectrum(m, 4, 2);
  const Eigen::MatrixXd& rest = s.rest;
  CageRegularization r(s.G, rest, 1.0);
  r.set_relative_weight(1.0);
  ASSERT_TRUE(r.active());
  Eigen::Matrix3d A = random_matrix(3, 3, 3);
  const Eigen::RowVector3d t(0.3, -2.0, 5.0);
  const Eigen::MatrixXd affine = (rest * A.transpose()).rowwise() + t;
  const Eigen::MatrixXd other = random_matrix(m, 3, 4);
  EXPECT_LE(r.energy(affine), 1e-12 * r.energy(other));
  EXPECT_LE(r.gradient(affine).norm(), 1e-12 * r.gradient(other).norm() * affine.norm() / other.norm() + 1e-14);
  EXPECT_LE(std::abs(r.energy(rest)), 1e-14);
}

TEST(CageRegularization, GradientAndHessianProductsMatchFiniteDifferences) {
  const int m = 24;
  const Spectrum s = spectrum(m, 3, 5);
  CageRegularization r(s.G, s.rest, 2.5);
  r.set_relative_weight(0.3);
  const Eigen::MatrixXd P = random_matrix(m, 3, 7), V = random_matrix(m, 3, 8);
  const double h = 1e-5;
  const double fd = (r.energy(P + h * V) - r.energy(P - h * V)) / (2 * h);
  const double analytic = (V.array() * r.gradient(P).array()).sum();
  EXPECT_NEAR(fd, analytic, 1e-7 * std::abs(analytic));
  // R is quadratic: the gradient is linear in P with the Hessian product as its slope.
  EXPECT_LE((r.gradient(P + V) - r.gradient(P) - r.hessian_times(V)).norm(), 1e-12 * r.hessian_times(V).norm());
  const Eigen::MatrixXd H = r.penalty();
  EXPECT_LE((H - H.transpose()).norm(), 1e-15 * H.norm());
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H).eigenvalues().minCoeff(), -1e-12 * H.norm());
}

TEST(CageRegularization, DampsOnlyTheNearNullMotionsOfTheCage) {
  const int m = 40;
  const Spectrum s = spectrum(m, 5, 9);
  CageRegularization r(s.G, s.rest, 1.0);
  r.set_relative_weight(1.0);
  const Eigen::MatrixXd& H = r.penalty();
  for (int k = 4; k < 9; ++k) {  // weak: damped fully (the filter is 1 - 1e-8 there)
    const Eigen::VectorXd v = s.Q.col(k);
    EXPECT_NEAR(v.dot(H * v), 1.0, 1e-6) << "weak direction " << k;
  }
  for (int k = 0; k < 4; ++k)  // the affine maps: free
    EXPECT_LE(std::abs(s.Q.col(k).dot(H * s.Q.col(k))), 1e-12) << "affine direction " << k;
  for (int k = 9; k < m; ++k) {  // sound (lambda >= 1e-3): (tau / lambda)^2 <= 1e-4
    const Eigen::VectorXd v = s.Q.col(k);
    EXPECT_LE(v.dot(H * v), 1.0001 * std::pow(CageRegularization::kWeakEigenvalue / s.lambda[k], 2))
        << "sound direction " << k << " (lambda " << s.lambda[k] << ")";
  }
  r.set_relative_weight(0.0);
  EXPECT_FALSE(r.active());
  EXPECT_EQ(r.energy(random_matrix(m, 3, 10)), 0.0);
}

// ---- in the solver

double diagonal(const Eigen::MatrixXd& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

struct Pull {
  Vertices mesh, cage;
};

// Fixes the 5% lowest vertices along `fixed_axis`, pulls the 5% highest along `moving_axis` up (+y) by
// `pull` of the diagonal, and solves with each relative cage regularisation in turn, each solve going on from
// where the last one converged.
std::vector<Pull> pulls(const Mesh& mesh, const Mesh& cage, double pull, int fixed_axis, int moving_axis,
                        const std::vector<double>& regularizations, JacobianMode mode = JacobianMode::Fast) {
  Deformer d(mesh, cage);
  SolverOptions o = d.options();
  o.jacobian = mode;
  d.set_options(o);
  const int n = static_cast<int>(mesh.V.rows());
  const auto by_axis = [&](int axis) {
    std::vector<int> v(n);
    std::iota(v.begin(), v.end(), 0);
    std::stable_sort(v.begin(), v.end(), [&](int a, int b) { return mesh.V(a, axis) < mesh.V(b, axis); });
    return v;
  };
  std::vector<int> fixed = by_axis(fixed_axis), moving;
  fixed.resize(n / 20);
  std::vector<char> is_fixed(n, 0);
  for (int v : fixed) is_fixed[v] = 1;
  const std::vector<int> order = by_axis(moving_axis);
  for (auto it = order.rbegin(); it != order.rend() && static_cast<int>(moving.size()) < n / 20; ++it)
    if (!is_fixed[*it]) moving.push_back(*it);
  d.set_handles({fixed, moving});
  Vertices T(fixed.size() + moving.size(), 3);
  int r = 0;
  for (int v : fixed) T.row(r++) = mesh.V.row(v);
  for (int v : moving) T.row(r++) = mesh.V.row(v) + Eigen::RowVector3d(0, pull * diagonal(mesh.V), 0);
  d.set_targets(T);
  std::vector<Pull> out;
  for (double regularization : regularizations) {
    o.cage_regularization = regularization;
    d.set_options(o);
    const StepResult result = d.solve();
    EXPECT_TRUE(result.converged) << result.stop_reason;
    EXPECT_NEAR(signed_volume(d.positions(), mesh.F), d.rest_volume(), 1e-8 * std::abs(d.rest_volume()));
    out.push_back({d.positions(), d.cage_positions()});
  }
  return out;
}

Pull pull(const Mesh& mesh, const Mesh& cage, double pull, int fixed_axis, int moving_axis, double regularization,
          JacobianMode mode = JacobianMode::Fast) {
  return pulls(mesh, cage, pull, fixed_axis, moving_axis, {regularization}, mode)[0];
}

double mesh_change(const Pull& a, const Pull& b, const Mesh& mesh) {
  return (a.mesh - b.mesh).rowwise().norm().maxCoeff() / diagonal(mesh.V);
}

TEST(CageRegularization, DefaultIsOnAndKeepsTheRestPose) {
  EXPECT_GT(SolverOptions().cage_regularization, 0.0);
  const Example bar = make_example("bar");
  Deformer d(bar.mesh, bar.cage);
  const StepResult r = d.solve();  // no handles moved: nothing to do
  EXPECT_LE((d.positions() - bar.mesh.V).norm(), 1e-12 * bar.mesh.V.norm());
  EXPECT_EQ(d.cage_positions(), bar.cage.V);
  (void)r;
}

TEST(CageRegularization, LeavesTheBuiltInBarsMeshAsItWas) {
  const Example bar = make_example("bar");
  for (JacobianMode mode : {JacobianMode::Fast, JacobianMode::Exact}) {
    const Pull off = pull(bar.mesh, bar.cage, 0.15, 0, 0, 0.0, mode);
    const Pull on = pull(bar.mesh, bar.cage, 0.15, 0, 0, SolverOptions().cage_regularization, mode);
    EXPECT_LT(mesh_change(on, off, bar.mesh), 1e-4);
  }
}

// The shared models: the meshes of sound cages do not move measurably; the cow's cage (influence ratio
// ~5e-9: seven cage motions barely move the mesh) no longer grows from a diagonal of 42 to 543.
struct SharedCase {
  const char* mesh;
  const char* cage;
  int fixed_axis, moving_axis;
};

class SoundCage : public ::testing::TestWithParam<SharedCase> {};

TEST_P(SoundCage, MeshMovesByLessThan1e4OfTheDiagonal) {
  const SharedCase c = GetParam();
  SD_REQUIRE_SHARED_DATA(c.mesh);
  SD_REQUIRE_SHARED_DATA(c.cage);
  const Mesh mesh = test::load_shared_mesh(c.mesh), cage = test::load_shared_mesh(c.cage);
  // The regularised solve goes on from the unregularised minimiser: the pull has several local minima a few 1e-3 of
  // the diagonal apart (on the hand bones two solves that differ only in rounding found two), and what is measured
  // is how far the term moves a minimiser, not which one a solve from rest finds.
  const std::vector<Pull> solves =
      pulls(mesh, cage, 0.15, c.fixed_axis, c.moving_axis, {0.0, SolverOptions().cage_regularization});
  const double change = mesh_change(solves[1], solves[0], mesh);
  std::cout << "[          ] " << c.mesh << ": the regularisation moves the mesh by " << change << " of the diagonal\n";
  EXPECT_LT(change, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(SharedData, SoundCage,
                         ::testing::Values(SharedCase{"gargoyle.obj", "gargoyle_cage_v67.obj", 1, 1},
                                           SharedCase{"armadillo.obj", "armadillo_cage.obj", 1, 1},
                                           SharedCase{"handbones.obj", "handbones_cage.obj", 1, 1}),
                         [](const ::testing::TestParamInfo<SharedCase>& info) {
                           std::string name = info.param.mesh;
                           return name.substr(0, name.find('.'));
                         });

TEST(CageRegularization, CowCageStaysWithinOneAndAHalfItsRestDiagonal) {
  SD_REQUIRE_SHARED_DATA("cow.obj");
  SD_REQUIRE_SHARED_DATA("cow_cage.obj");
  const Mesh mesh = test::load_shared_mesh("cow.obj"), cage = test::load_shared_mesh("cow_cage.obj");
  const double rest = diagonal(cage.V);
  const Pull off = pull(mesh, cage, 0.05, 1, 0, 0.0);
  EXPECT_GT(diagonal(off.cage), 3 * rest) << "the unregularised cow cage no longer drifts: is the test still needed?";
  const Pull on = pull(mesh, cage, 0.05, 1, 0, SolverOptions().cage_regularization);
  EXPECT_LT(diagonal(on.cage), 1.5 * rest);
  std::cout << "[          ] cow cage diagonal: rest " << rest << ", unregularised " << diagonal(off.cage)
            << ", regularised " << diagonal(on.cage) << "\n";
}

}  // namespace
}  // namespace sd
