#include "core/solver/internal/energy/laplacian_coordinates.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/mesh/cotan_laplacian.h"
#include "core/error.h"
#include "core/mesh/shapes.h"
#include "test_support.h"

namespace sd {
namespace {

std::vector<std::pair<std::string, Mesh>> fixture_meshes() {
  return {{"icosphere(3)", make_icosphere(3, 1.0)},
          {"capsule", make_capsule(2.0, 0.5, 8, 10, 24)},
          {"box(3)", make_box(2, 3, 4, 3)}};
}

// Relative Frobenius distance between delta_hat(X0) and L X0.
double rest_mismatch(const Mesh& m, int* fallbacks = nullptr) {
  const Eigen::SparseMatrix<double> L = cotan_laplacian(m.V, m.F);
  const LaplacianCoordinates lc(m.V, m.F, L);
  if (fallbacks) *fallbacks = lc.fallback_count();
  const Vertices delta = L * m.V;
  return (lc.evaluate(m.V) - delta).norm() / delta.norm();
}

TEST(LaplacianCoordinates, RestPoseReproducesLX0) {
  for (const auto& [name, mesh] : fixture_meshes()) {
    int fallbacks = -1;
    EXPECT_LE(rest_mismatch(mesh, &fallbacks), 1e-10) << name;
    std::cout << "[          ] " << name << ": " << mesh.V.rows() << " vertices, " << fallbacks
              << " fallback vertices\n";
  }
}

TEST(LaplacianCoordinates, SharedDataRestPoseReproducesLX0) {
  for (const char* name : {"gargoyle.obj", "armadillo.obj", "moomoo.obj", "spot.obj"}) {
    SD_REQUIRE_SHARED_DATA(name);
    const Mesh mesh = test::load_shared_mesh(name);
    int fallbacks = -1;
    EXPECT_LE(rest_mismatch(mesh, &fallbacks), 1e-10) << name;
    std::cout << "[          ] " << name << ": " << mesh.V.rows() << " vertices, " << fallbacks
              << " fallback vertices\n";
  }
}

TEST(LaplacianCoordinates, NoFallbackOnACapsule) {
  const Mesh capsule = make_capsule(3.0, 0.4, 12, 30, 32);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(capsule.V, capsule.F);
  EXPECT_EQ(LaplacianCoordinates(capsule.V, capsule.F, L).fallback_count(), 0);
}

// On a flat box face L X0 vanishes, so those vertices must take the fallback (and still reproduce L X0).
TEST(LaplacianCoordinates, FlatVerticesFallBack) {
  const Mesh box = make_box(1, 1, 1, 4);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(box.V, box.F);
  const LaplacianCoordinates lc(box.V, box.F, L);
  EXPECT_GE(lc.fallback_count(), 6 * 9);  // the 3x3 interior vertices of each face
  EXPECT_TRUE(lc.evaluate(box.V).allFinite());
}

TEST(LaplacianCoordinates, OneRingFollowsTheOutwardFaces) {
  const Mesh s = make_icosphere(1, 1.0);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(s.V, s.F);
  const LaplacianCoordinates lc(s.V, s.F, L);
  for (int i = 0; i < s.V.rows(); ++i) {
    const std::vector<int> ring = lc.one_ring(i);
    const int k = static_cast<int>(ring.size());
    ASSERT_GE(k, 5);
    for (int t = 0; t < k; ++t) {
      const Eigen::RowVector3d c = (s.V.row(ring[(t + k - 1) % k]) - s.V.row(i)).cross(s.V.row(ring[t]) - s.V.row(i));
      EXPECT_GT(c.dot(s.V.row(i)), 0.0) << "vertex " << i;  // outward on a sphere about the origin
    }
  }
}

TEST(LaplacianCoordinates, NonManifoldOrMisorientedMeshThrows) {
  Mesh s = make_icosphere(1, 1.0);
  std::swap(s.F(0, 1), s.F(0, 2));  // one flipped triangle
  test::expect_error([&] { LaplacianCoordinates(s.V, s.F, cotan_laplacian(s.V, s.F)); }, "cannot be ordered",
                     ErrorCode::InvalidMesh);
  // Two tetrahedra sharing vertex 0: its triangles form two fans.
  const Mesh a = make_icosphere(0, 1.0);
  Mesh bowtie = test::join_meshes(a, a);
  bowtie.V.bottomRows(a.V.rows()).rowwise() += Eigen::RowVector3d(2 * a.V(0, 0), 2 * a.V(0, 1), 2 * a.V(0, 2));
  for (int f = 0; f < bowtie.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (bowtie.F(f, k) == a.V.rows()) bowtie.F(f, k) = 0;  // the second's vertex 0 is the first's
  test::expect_error([&] { LaplacianCoordinates(bowtie.V, bowtie.F, cotan_laplacian(bowtie.V, bowtie.F)); },
                     "more than one fan", ErrorCode::InvalidMesh);
}

// Open meshes: a sphere with a hole, a capsule cut open at both ends, a flat square (every boundary vertex's
// delta is tangential).
std::vector<std::pair<std::string, Mesh>> open_meshes() {
  return {{"icosphere with a hole",
           test::drop_faces(make_icosphere(3, 1.0), [](const Eigen::RowVector3d& c) { return c.z() > 0.8; })},
          {"open capsule", test::drop_faces(make_capsule(2.0, 0.5, 6, 6, 16),
                                            [](const Eigen::RowVector3d& c) { return std::abs(c.x()) > 1.2; })},
          {"flat square",
           test::drop_faces(make_box(2, 2, 2, 4), [](const Eigen::RowVector3d& c) { return c.z() < 0.99; })}};
}

// The boundary rows keep delta_hat(X0) = L' X0 exact (the rest pose is a fixed point of the energy), L' has
// zero row sums, and equals L away from the boundary.
TEST(LaplacianCoordinates, OpenMeshRestPoseReproducesItsLaplacianRows) {
  for (const auto& [name, mesh] : open_meshes()) {
    const Eigen::SparseMatrix<double> L = cotan_laplacian(mesh.V, mesh.F);
    const LaplacianCoordinates lc(mesh.V, mesh.F, L);
    ASSERT_GT(lc.boundary_count(), 0) << name;
    EXPECT_EQ(lc.fallback_count() > 0, name == "flat square") << name;  // only a flat delta of 0 falls back
    const Eigen::SparseMatrix<double> Lb = lc.laplacian();
    const Vertices rows = Lb * mesh.V;
    const double scale = Vertices(L * mesh.V).norm();
    EXPECT_LE((lc.evaluate(mesh.V) - rows).norm(), 1e-10 * scale) << name;
    EXPECT_LE(lc.laplacian_residual(mesh.V).norm(), 1e-10 * scale) << name;
    EXPECT_LE(Eigen::VectorXd(Lb * Eigen::VectorXd::Ones(mesh.V.rows())).cwiseAbs().maxCoeff(), 1e-12 * Lb.norm())
        << name;
    for (int i = 0; i < mesh.V.rows(); ++i) {
      if (lc.is_boundary(i)) continue;
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, i); it; ++it)  // column i = row i (L is symmetric)
        EXPECT_EQ(Lb.coeff(i, it.row()), it.value()) << name << " vertex " << i;
    }
  }
}

TEST(LaplacianCoordinates, ClosedMeshKeepsTheCotangentLaplacian) {
  const Mesh s = make_icosphere(2, 1.0);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(s.V, s.F);
  const LaplacianCoordinates lc(s.V, s.F, L);
  EXPECT_EQ(lc.boundary_count(), 0);
  EXPECT_EQ((Eigen::MatrixXd(lc.laplacian()) - Eigen::MatrixXd(L)).cwiseAbs().maxCoeff(), 0.0);
}

// A boundary vertex's ring starts at its open fan's first neighbour: every consecutive pair after it spans an
// outward triangle, and the pair (last, first) spans none.
TEST(LaplacianCoordinates, BoundaryFansAreOrderedOpen) {
  const Mesh m = test::drop_faces(make_icosphere(2, 1.0), [](const Eigen::RowVector3d& c) { return c.z() > 0.7; });
  const LaplacianCoordinates lc(m.V, m.F, cotan_laplacian(m.V, m.F));
  int boundary = 0;
  for (int i = 0; i < m.V.rows(); ++i) {
    const std::vector<int> ring = lc.one_ring(i);
    const int k = static_cast<int>(ring.size());
    for (int t = lc.is_boundary(i) ? 1 : 0; t < k; ++t) {
      const Eigen::RowVector3d c = (m.V.row(ring[(t + k - 1) % k]) - m.V.row(i)).cross(m.V.row(ring[t]) - m.V.row(i));
      EXPECT_GT(c.dot(m.V.row(i)), 0.0) << "vertex " << i;
    }
    boundary += lc.is_boundary(i);
  }
  EXPECT_GT(boundary, 5);
  EXPECT_EQ(boundary, lc.boundary_count());
}

Vertices perturbed(const Vertices& V, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  Vertices X = V;
  for (int i = 0; i < X.size(); ++i) X.data()[i] += u(rng);
  return X;
}

Eigen::VectorXd flat(const Vertices& X) { return Eigen::Map<const Eigen::VectorXd>(X.data(), X.size()); }

// The energy's residual L X - delta_hat(X), computed in one pass from the ring edges, against the sparse
// product minus evaluate(), at rest (both ~0) and at a perturbed pose.
TEST(LaplacianCoordinates, ResidualIsLaplacianMinusCoordinates) {
  const Mesh mesh = make_capsule(2.0, 0.5, 4, 4, 10);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(mesh.V, mesh.F);
  const LaplacianCoordinates lc(mesh.V, mesh.F, L);
  for (double amount : {0.0, 0.05}) {
    const Vertices X = perturbed(mesh.V, amount, 13);
    const Vertices expected = L * X - lc.evaluate(X);
    const Vertices residual = lc.laplacian_residual(X);
    const double scale = Vertices(L * X).cwiseAbs().maxCoeff();
    EXPECT_LE((residual - expected).cwiseAbs().maxCoeff(), 1e-13 * scale) << amount;
    if (amount > 0) EXPECT_GT(residual.cwiseAbs().maxCoeff(), 1e-3 * scale);  // a real residual, not ~0
  }
}

// Every column of the analytic Jacobian against central differences at a non-rest X.
TEST(LaplacianCoordinates, JacobianMatchesCentralDifferencesColumnByColumn) {
  for (const auto& [name, mesh] : std::vector<std::pair<std::string, Mesh>>{
           {"icosphere(2)", make_icosphere(2, 1.0)},
           {"capsule", make_capsule(2.0, 0.5, 4, 4, 10)},
           {"open capsule", test::drop_faces(make_capsule(2.0, 0.5, 4, 4, 10),
                                             [](const Eigen::RowVector3d& c) { return c.x() > 1.0; })}}) {
    const LaplacianCoordinates lc(mesh.V, mesh.F, cotan_laplacian(mesh.V, mesh.F));
    const Vertices X = perturbed(mesh.V, 0.03, 11);
    const Eigen::MatrixXd J = Eigen::MatrixXd(lc.jacobian(X));
    ASSERT_EQ(J.rows(), 3 * mesh.V.rows());
    const double eps = 1e-6;
    double worst = 0;
    for (int col = 0; col < J.cols(); ++col) {
      Vertices plus = X, minus = X;
      plus.data()[col] += eps;
      minus.data()[col] -= eps;
      const Eigen::VectorXd fd = (flat(lc.evaluate(plus)) - flat(lc.evaluate(minus))) / (2 * eps);
      worst = std::max(worst, (fd - J.col(col)).norm() / J.col(col).norm());
    }
    EXPECT_LE(worst, 1e-6) << name;
  }
}

// Directional derivatives on larger meshes: J v against central differences along random v.
TEST(LaplacianCoordinates, JacobianMatchesDirectionalDifferences) {
  for (const auto& [name, mesh] : fixture_meshes()) {
    const LaplacianCoordinates lc(mesh.V, mesh.F, cotan_laplacian(mesh.V, mesh.F));
    const Vertices X = perturbed(mesh.V, 0.02, 5);
    const Eigen::SparseMatrix<double> J = lc.jacobian(X);
    for (unsigned trial = 0; trial < 3; ++trial) {
      const Vertices V = perturbed(Vertices::Zero(X.rows(), 3), 1.0, 100 + trial);
      const double eps = 1e-6;
      const Eigen::VectorXd fd = (flat(lc.evaluate(X + eps * V)) - flat(lc.evaluate(X - eps * V))) / (2 * eps);
      const Eigen::VectorXd Jv = J * flat(V);
      EXPECT_LE((fd - Jv).norm(), 1e-6 * Jv.norm()) << name << " trial " << trial;
    }
  }
}

TEST(LaplacianCoordinates, RotatesWithTheMesh) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  std::vector<std::pair<std::string, Mesh>> meshes = fixture_meshes();
  for (auto& m : open_meshes()) meshes.push_back(m);
  for (const auto& [name, mesh] : meshes) {
    const LaplacianCoordinates lc(mesh.V, mesh.F, cotan_laplacian(mesh.V, mesh.F));
    const Vertices X = perturbed(mesh.V, 0.05, 9);
    const Vertices base = lc.evaluate(X);
    const Vertices residual = lc.laplacian_residual(X);  // with the boundary rows' edge terms, on open meshes
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::Matrix3d R = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
      const Eigen::RowVector3d t(g(rng), g(rng), g(rng));
      const Vertices moved = (X * R.transpose()).rowwise() + t;
      const Vertices expected = base * R.transpose();
      EXPECT_LE((lc.evaluate(moved) - expected).norm(), 1e-12 * base.norm()) << name;
      EXPECT_LE((lc.laplacian_residual(moved) - residual * R.transpose()).norm(),
                1e-11 * (residual.norm() + base.norm()))
          << name;
    }
  }
}

// A one-ring squashed to a point must not produce NaN in delta_hat or its Jacobian.
TEST(LaplacianCoordinates, CollapsedOneRingStaysFinite) {
  const Mesh s = make_icosphere(2, 1.0);
  const LaplacianCoordinates lc(s.V, s.F, cotan_laplacian(s.V, s.F));
  Vertices X = s.V;
  const int i = 0;
  for (int j : lc.one_ring(i)) X.row(j) = X.row(i);
  EXPECT_TRUE(lc.evaluate(X).allFinite());
  const Eigen::SparseMatrix<double> J = lc.jacobian(X);
  EXPECT_TRUE(Eigen::MatrixXd(J).allFinite());
  Vertices all_zero = Vertices::Zero(s.V.rows(), 3);
  EXPECT_TRUE(lc.evaluate(all_zero).allFinite());
  EXPECT_TRUE(Eigen::MatrixXd(lc.jacobian(all_zero)).allFinite());
}

}  // namespace
}  // namespace sd
