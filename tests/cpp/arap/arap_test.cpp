#include "core/arap/arap.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "core/error.h"
#include "core/mesh/shapes.h"

namespace sd {
namespace {

void expect_proper_rotation(const Eigen::Matrix3d& R) {
  ASSERT_TRUE(R.allFinite());
  EXPECT_LE((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
}

TEST(ArapRotation, RecoversARotationFromItsCovariance) {
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  const Eigen::Matrix3d Q = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d e0(g(rng), g(rng), g(rng));
    S += e0 * (Q * e0).transpose();
  }
  const Eigen::Matrix3d R = arap_best_rotation(S);
  expect_proper_rotation(R);
  EXPECT_LE((R - Q).norm(), 1e-12);
}

// A mirrored point set: the unconstrained optimum is a reflection; the answer must be the best proper
// rotation, which flips the direction of the smallest singular value.
TEST(ArapRotation, ReflectionCovarianceGivesAProperRotation) {
  Eigen::Matrix3d S = Eigen::Vector3d(3.0, 2.0, -1.0).asDiagonal();  // e = diag(1,1,-1) e0 for axis points
  const Eigen::Matrix3d R = arap_best_rotation(S);
  expect_proper_rotation(R);
  EXPECT_LE((R - Eigen::Matrix3d::Identity()).norm(), 1e-12);  // trace(R S) = 3 + 2 - 1 is the best
  // Same in a rotated frame.
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d R2 = arap_best_rotation(Q * S * Q.transpose());
  expect_proper_rotation(R2);
  EXPECT_LE((R2 - Eigen::Matrix3d::Identity()).norm(), 1e-12);
}

TEST(ArapRotation, DegenerateCovariancesGiveFiniteRotations) {
  EXPECT_EQ(arap_best_rotation(Eigen::Matrix3d::Zero()), Eigen::Matrix3d::Identity());
  Eigen::Matrix3d bad = Eigen::Matrix3d::Identity();
  bad(1, 2) = std::nan("");
  EXPECT_EQ(arap_best_rotation(bad), Eigen::Matrix3d::Identity());
  bad(1, 2) = INFINITY;
  EXPECT_EQ(arap_best_rotation(bad), Eigen::Matrix3d::Identity());
  // Rank 1 (all edges parallel) and rank 2 (flat one-ring) and a tiny scale.
  const Eigen::Vector3d a(1, 2, 3), b(-2, 0.5, 1);
  expect_proper_rotation(arap_best_rotation(a * b.transpose()));
  expect_proper_rotation(arap_best_rotation(a * a.transpose() + b * b.transpose()));
  expect_proper_rotation(arap_best_rotation(1e-300 * (a * b.transpose())));
}

// Covariances of several kinds (generic, flat and nearly flat one-rings, mirrored, noisy): the answer is
// a proper rotation that no random rotation and no small turn of it beats on trace(R S).
TEST(ArapRotation, IsTheBestProperRotationOnVariedCovariances) {
  std::mt19937 rng(4);
  std::normal_distribution<double> g;
  auto random_rotation = [&] {
    return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
  };
  for (int trial = 0; trial < 400; ++trial) {
    const int kind = trial % 5;
    const Eigen::Matrix3d Q = random_rotation();
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
    for (int j = 0; j < 6; ++j) {
      Eigen::Vector3d e0(g(rng), g(rng), g(rng));
      if (kind == 1) e0.z() = 0;      // flat one-ring: rank 2
      if (kind == 2) e0.z() *= 1e-4;  // nearly flat
      Eigen::Vector3d e = Q * e0;
      if (kind == 3) e = Q * Eigen::Vector3d(e0.x(), e0.y(), -e0.z());  // mirrored
      if (kind == 4) e += 0.5 * Eigen::Vector3d(g(rng), g(rng), g(rng));
      S += e0 * e.transpose();
    }
    const Eigen::Matrix3d R = arap_best_rotation(S);
    expect_proper_rotation(R);
    const double best = (R * S).trace(), tol = 1e-10 * S.norm();
    for (int k = 0; k < 50; ++k) EXPECT_LE((random_rotation() * S).trace(), best + tol) << "kind " << kind;
    for (int axis = 0; axis < 3; ++axis)
      for (double angle : {1e-3, -1e-3}) {
        const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
        EXPECT_LE((turn * R * S).trace(), best + tol) << "kind " << kind << " trial " << trial;
      }
  }
}

Mesh bar() { return make_capsule(4.0, 0.5, 6, 20, 20); }

// Vertices of the bar beyond |x| > 1.6: the two handle regions.
std::vector<int> bar_handles(const Mesh& m, bool left, bool right) {
  std::vector<int> out;
  for (int i = 0; i < m.V.rows(); ++i)
    if ((left && m.V(i, 0) < -1.6) || (right && m.V(i, 0) > 1.6)) out.push_back(i);
  return out;
}

Vertices rows_of(const Vertices& V, const std::vector<int>& idx) {
  Vertices out(static_cast<int>(idx.size()), 3);
  for (size_t k = 0; k < idx.size(); ++k) out.row(static_cast<int>(k)) = V.row(idx[k]);
  return out;
}

TEST(Arap, CommonTranslationOfEveryHandleTranslatesTheMesh) {
  const Mesh m = bar();
  ArapSolver arap(m.V, m.F);
  const std::vector<int> handles = bar_handles(m, true, true);
  arap.set_handles(handles);
  const Eigen::RowVector3d t(0.3, -1.2, 0.7);
  const Vertices targets = rows_of(m.V, handles).rowwise() + t;
  Vertices X = m.V;
  for (int it = 0; it < 5; ++it) arap.iterate(X, targets);
  const Vertices expected = m.V.rowwise() + t;
  EXPECT_LE((X - expected).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE(arap.energy(X), 1e-18);
}

TEST(Arap, RigidMotionOfEveryHandleMovesTheMeshRigidly) {
  const Mesh m = make_icosphere(2, 1.0);
  ArapSolver arap(m.V, m.F);
  std::vector<int> handles;  // every fifth vertex, spread over the sphere
  for (int i = 0; i < m.V.rows(); i += 5) handles.push_back(i);
  arap.set_handles(handles);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::RowVector3d t(0.5, 0.1, -0.2);
  const Vertices expected = (m.V * Q.transpose()).rowwise() + t;
  const Vertices targets = rows_of(expected, handles);
  Vertices X = m.V;
  IterationStats last;
  for (int it = 0; it < 200 && (it < 2 || last.step > 1e-13); ++it) last = arap.iterate(X, targets);
  EXPECT_LE((X - expected).cwiseAbs().maxCoeff(), 1e-9) << "after " << last.iteration << " iterations";
  EXPECT_LE(last.energy, 1e-18);
}

// A bar bent by turning its right end 90 degrees about z while the left end stays.
struct Bend {
  Mesh mesh = bar();
  std::vector<int> handles = bar_handles(mesh, true, true);
  Vertices targets;
  Bend() {
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d pivot(1.6, 0, 0);
    targets = rows_of(mesh.V, handles);
    for (int k = 0; k < targets.rows(); ++k)
      if (targets(k, 0) > 0)
        targets.row(k) = (Q * (targets.row(k).transpose() - pivot) + pivot + Eigen::Vector3d(-0.8, 0.8, 0)).transpose();
  }
};

TEST(Arap, EnergyNeverIncreasesAndHandlesLandExactly) {
  Bend bend;
  ArapSolver arap(bend.mesh.V, bend.mesh.F);
  arap.set_handles(bend.handles);
  Vertices X = bend.mesh.V;
  double previous = INFINITY;
  for (int it = 0; it < 60; ++it) {
    const IterationStats s = arap.iterate(X, bend.targets);
    ASSERT_TRUE(std::isfinite(s.energy));
    EXPECT_LE(s.energy, previous * (1 + 1e-12)) << "iteration " << s.iteration;
    EXPECT_NEAR(s.energy, arap.energy(X), 1e-12 * s.energy);
    previous = s.energy;
    for (size_t k = 0; k < bend.handles.size(); ++k)
      ASSERT_EQ(X.row(bend.handles[k]), bend.targets.row(static_cast<int>(k)));
  }
  EXPECT_GT(previous, 0.0);  // a real bend is not rigid
}

// The step-through's halves: each lowers the energy with the other half's variables fixed (or keeps it), the
// local half moves no vertex, and local then global is exactly one plain local-global iteration.
TEST(Arap, HalfStepsLowerTheEnergyAndTogetherMakeOnePlainIteration) {
  Bend bend;
  ArapSolver halves(bend.mesh.V, bend.mesh.F), whole(bend.mesh.V, bend.mesh.F);
  halves.set_handles(bend.handles);
  whole.set_handles(bend.handles);
  whole.set_acceleration(0);
  Vertices X = bend.mesh.V, Y = bend.mesh.V;
  double angle = 0;
  for (int it = 0; it < 5; ++it) {
    const Vertices before = X;
    const ArapHalfStep local = halves.local_half_step(X);
    EXPECT_TRUE(local.local);
    EXPECT_EQ(X, before);
    EXPECT_EQ(local.step, 0.0);
    EXPECT_LE(local.energy_after, local.energy_before * (1 + 1e-12) + 1e-15) << "local, iteration " << it;
    EXPECT_NEAR(local.energy_after, halves.energy(X), 1e-12 * (1 + local.energy_after));
    const ArapHalfStep global = halves.global_half_step(X, bend.targets);
    EXPECT_FALSE(global.local);
    // The global step starts with the handles at their targets: from the second iteration on they are there.
    if (it > 0) EXPECT_NEAR(global.energy_before, local.energy_after, 1e-12 * (1 + local.energy_after));
    EXPECT_LE(global.energy_after, global.energy_before * (1 + 1e-12)) << "global, iteration " << it;
    EXPECT_NEAR(global.step, (X - before).rowwise().norm().maxCoeff(), 1e-15);
    for (size_t k = 0; k < bend.handles.size(); ++k)
      ASSERT_EQ(X.row(bend.handles[k]), bend.targets.row(static_cast<int>(k)));
    whole.iterate(Y, bend.targets);
    EXPECT_LE((X - Y).cwiseAbs().maxCoeff(), 1e-12) << "local + global = one iteration, iteration " << it;
    EXPECT_GE(local.max_rotation, local.mean_rotation);
    angle = local.max_rotation;
  }
  EXPECT_GT(angle, 0.1);  // the bend turns the far end's one-rings
  EXPECT_THROW(halves.global_half_step(X, Vertices(1, 3)), Error);
}

TEST(Arap, BarBendIsFiniteWithNoInvertedTriangles) {
  Bend bend;
  const Mesh& m = bend.mesh;
  ArapSolver arap(m.V, m.F);
  arap.set_handles(bend.handles);
  Vertices X = m.V;
  for (int it = 0; it < 100; ++it) arap.iterate(X, bend.targets);
  ASSERT_TRUE(X.allFinite());
  // A face is inverted when its normal opposes its rest normal carried by the local ARAP rotation.
  int inverted = 0, against_rest = 0;
  for (int f = 0; f < m.F.rows(); ++f) {
    const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2);
    const Eigen::Vector3d n0 = (m.V.row(b) - m.V.row(a)).cross(m.V.row(c) - m.V.row(a)).transpose();
    const Eigen::Vector3d n = (X.row(b) - X.row(a)).cross(X.row(c) - X.row(a)).transpose();
    if (n.dot(arap.rotations()[a] * n0) <= 0) ++inverted;
    if (n.dot(n0) <= 0) ++against_rest;
  }
  EXPECT_EQ(inverted, 0);
  std::cout << "[          ] " << m.V.rows() << " vertices, " << against_rest
            << " faces turned 90 degrees or more from their rest normal, " << inverted << " inverted, "
            << arap.clamped_weight_count() << " clamped weights\n";
}

TEST(Arap, NoHandlesLeavesTheMeshAndComponentsWithoutHandlesStay) {
  const Mesh s = make_icosphere(1, 1.0);
  ArapSolver lone(s.V, s.F);
  Vertices X = s.V * 1.1;
  const Vertices before = X;
  lone.set_handles({});
  lone.iterate(X, Vertices(0, 3));
  EXPECT_EQ(X, before);

  // Two spheres, handles on the first only: the second is not touched.
  Mesh two;
  const int n = static_cast<int>(s.V.rows());
  two.V.resize(2 * n, 3);
  two.V << s.V, (s.V.rowwise() + Eigen::RowVector3d(3, 0, 0));
  two.F.resize(2 * s.F.rows(), 3);
  two.F << s.F, (s.F.array() + n).matrix();
  ArapSolver arap(two.V, two.F);
  arap.set_handles({0, 1});
  Vertices Y = two.V;
  Vertices targets = rows_of(two.V, {0, 1}).rowwise() + Eigen::RowVector3d(0, 1, 0);
  arap.iterate(Y, targets);
  ASSERT_TRUE(Y.allFinite());
  EXPECT_EQ(Y.bottomRows(n), two.V.bottomRows(n));
  EXPECT_LE((Y.topRows(n) - (s.V.rowwise() + Eigen::RowVector3d(0, 1, 0))).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(Arap, BadInputThrows) {
  const Mesh s = make_icosphere(1, 1.0);
  ArapSolver arap(s.V, s.F);
  EXPECT_THROW(arap.set_handles({3, 1}), Error);
  EXPECT_THROW(arap.set_handles({1, 1}), Error);
  EXPECT_THROW(arap.set_handles({-1}), Error);
  EXPECT_THROW(arap.set_handles({static_cast<int>(s.V.rows())}), Error);
  arap.set_handles({0, 5});
  Vertices X = s.V;
  EXPECT_THROW(arap.iterate(X, Vertices::Zero(1, 3)), Error);
  Vertices wrong = s.V.topRows(3);
  EXPECT_THROW(arap.iterate(wrong, Vertices::Zero(2, 3)), Error);
  Vertices targets = rows_of(s.V, {0, 5});
  targets(0, 0) = std::nan("");
  EXPECT_THROW(arap.iterate(X, targets), Error);
}

}  // namespace
}  // namespace sd
