#include "core/mesh/volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/mesh/shapes.h"
#include "core/parallel/thread_pool.h"
#include "test_support.h"

namespace sd {
namespace {

// A direction per vertex, entries uniform in [-0.2, 0.2]: a generic D for psi(V + t D).
Vertices random_directions(Eigen::Index rows, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  Vertices D(rows, 3);
  for (Eigen::Index i = 0; i < D.size(); ++i) D.data()[i] = u(rng);
  return D;
}

TEST(Volume, BoxIsExact) {
  for (int sub : {1, 2, 5}) {
    const Mesh box = make_box(2, 3, 4, sub);
    EXPECT_NEAR(signed_volume(box.V, box.F), 24.0, 1e-12) << sub;
  }
}

TEST(Volume, ReversedOrientationFlipsSign) {
  Mesh box = make_box(1, 2, 3, 2);
  box.F.col(1).swap(box.F.col(2));
  EXPECT_NEAR(signed_volume(box.V, box.F), -6.0, 1e-12);
}

// Inscribed icospheres approach the ball from below, the error shrinking about 4x per subdivision.
TEST(Volume, IcosphereConvergesToTheBall) {
  const double r = 1.7, ball = 4.0 / 3.0 * M_PI * r * r * r;
  double previous_error = 1e9;
  for (int level = 1; level <= 5; ++level) {
    const Mesh s = make_icosphere(level, r);
    const double v = signed_volume(s.V, s.F);
    const double error = ball - v;
    EXPECT_GT(error, 0.0) << level;
    EXPECT_LT(error, 0.3 * previous_error) << level;
    previous_error = error;
  }
  EXPECT_LT(previous_error / ball, 2e-3);
}

TEST(Volume, TranslationInvariant) {
  const Mesh capsule = make_capsule(2.0, 0.5, 6, 8, 16);
  const double v0 = signed_volume(capsule.V, capsule.F);
  Vertices moved = capsule.V;
  moved.rowwise() += Eigen::RowVector3d(10.0, -7.0, 3.5);
  EXPECT_NEAR(signed_volume(moved, capsule.F), v0, 1e-12 * 100 * std::abs(v0));
}

TEST(Volume, GradientMatchesCentralDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  for (const Mesh& m : {make_icosphere(2, 1.0), make_capsule(2.0, 0.5, 4, 5, 10), make_box(1, 2, 3, 2)}) {
    Vertices X = m.V;  // a generic (non-rest) configuration
    for (int i = 0; i < X.size(); ++i) X.data()[i] += jitter(rng);
    const Vertices G = volume_gradient(X, m.F);
    const double eps = 1e-5;
    Vertices fd(X.rows(), 3);
    for (int i = 0; i < X.rows(); ++i)
      for (int a = 0; a < 3; ++a) {
        Vertices plus = X, minus = X;
        plus(i, a) += eps;
        minus(i, a) -= eps;
        fd(i, a) = (signed_volume(plus, m.F) - signed_volume(minus, m.F)) / (2 * eps);
      }
    // psi is cubic, so central differences are exact up to eps^2 times a bounded third derivative.
    EXPECT_LE((fd - G).norm(), 1e-6 * G.norm());
  }
}

// The gradient of the enclosed volume of a sphere points outward along the vertex normal.
TEST(Volume, GradientPointsOutwardOnASphere) {
  const Mesh s = make_icosphere(3, 1.0);
  const Vertices G = volume_gradient(s.V, s.F);
  for (int i = 0; i < s.V.rows(); ++i) EXPECT_GT(G.row(i).dot(s.V.row(i)), 0.99 * G.row(i).norm()) << i;
}

// The cubic psi(V + t D) that the volume restoration solves: exact at any t (to rounding), and its slope at 0
// is grad psi . D.
TEST(Volume, AlongADirectionIsTheCubicOfTheMovedMesh) {
  const Mesh s = make_icosphere(3, 1.3);
  const Vertices D = random_directions(s.V.rows(), 5);
  const std::array<double, 4> k = volume_along(s.V, D, s.F, volume_reference(s.V, s.F));
  const double scale = std::abs(k[0]);
  for (double t : {0.0, 0.3, -0.7, 1.0, 2.5}) {
    const double cubic = k[0] + t * (k[1] + t * (k[2] + t * k[3]));
    EXPECT_NEAR(cubic, signed_volume(Vertices(s.V + t * D), s.F), 1e-12 * scale * (1 + std::abs(t * t * t))) << t;
  }
  EXPECT_NEAR(k[1], volume_gradient(s.V, s.F).cwiseProduct(D).sum(), 1e-12 * scale);
  EXPECT_GT(std::abs(k[3]), 1e-6 * scale);  // a real cubic: random directions do not cancel the t^3 term
}

// The gradient gathers each vertex's triangles in increasing order; a serial scatter over the triangles
// (the definition, docs/method.md section 5) adds them in the same order, so the two agree bit for bit, with any
// number of threads, also for a degenerate triangle that lists a vertex twice.
TEST(Volume, GradientGatherEqualsTheSerialScatterForAnyThreadCount) {
  Mesh s = make_icosphere(5, 1.0);  // 10242 vertices: several blocks of the parallel loops
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Eigen::Index i = 0; i < s.V.rows(); ++i) s.V.row(i) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
  s.F.conservativeResize(s.F.rows() + 1, 3);
  s.F.row(s.F.rows() - 1) << 7, 7, 9;  // degenerate
  const VolumeReference o = volume_reference(s.V, s.F);
  Vertices scatter = Vertices::Zero(s.V.rows(), 3);
  for (int f = 0; f < s.F.rows(); ++f) {
    const int a = s.F(f, 0), b = s.F(f, 1), c = s.F(f, 2);
    const Eigen::RowVector3d xa = s.V.row(a) - o, xb = s.V.row(b) - o, xc = s.V.row(c) - o;
    scatter.row(a) += xb.cross(xc);
    scatter.row(b) += xc.cross(xa);
    scatter.row(c) += xa.cross(xb);
  }
  scatter /= 6.0;
  const int saved = parallel::threads();
  const Vertices D = 0.1 * s.V.rowwise().reverse();
  parallel::set_threads(1);
  const double volume1 = signed_volume(s.V, s.F);
  const auto along1 = volume_along(s.V, D, s.F, o);
  for (int threads : {1, 2, 4}) {
    parallel::set_threads(threads);
    EXPECT_TRUE(volume_gradient(s.V, s.F) == scatter) << threads << " threads";
    EXPECT_EQ(signed_volume(s.V, s.F), volume1) << threads << " threads";
    EXPECT_TRUE(volume_along(s.V, D, s.F, o) == along1) << threads << " threads";
  }
  parallel::set_threads(saved);
  EXPECT_NEAR(along1[0], volume1, 1e-12 * std::abs(volume1));
}

// The sum is the same about any reference point (the surface is closed), to rounding.
TEST(Volume, AnyReferencePointGivesTheSameVolume) {
  const Mesh capsule = make_capsule(2.0, 0.5, 6, 8, 16);
  const double v0 = signed_volume(capsule.V, capsule.F);
  for (const VolumeReference& o :
       {VolumeReference(VolumeReference::Zero()), VolumeReference(0.3, -2.0, 1.0), VolumeReference(-5.0, 4.0, 7.0)})
    EXPECT_NEAR(signed_volume(capsule.V, capsule.F, o), v0, 1e-13 * v0) << o;
  // Near the origin (within half the diagonal's power of two) the reference is the origin itself: the sums are
  // bit for bit those made before it existed; far away, within that of the box's centre.
  EXPECT_EQ(volume_reference(capsule.V, capsule.F), VolumeReference::Zero());
  const Mesh far = test::translated(capsule, Eigen::RowVector3d(1e5 + 0.3, -2e5, 7.0));
  const VolumeReference centre = (far.V.colwise().minCoeff() + far.V.colwise().maxCoeff()) / 2;
  EXPECT_LE((volume_reference(far.V, far.F) - centre).cwiseAbs().maxCoeff(), 4.0 / 2);  // diagonal 3.2: s = 4
  EXPECT_EQ(signed_volume(capsule.V, capsule.F), signed_volume(capsule.V, capsule.F, VolumeReference::Zero()));
}

// A vertex that no triangle uses, or one that is not finite, does not move the reference point.
TEST(Volume, TheReferenceIsTheCentreOfTheVerticesTheTrianglesUse) {
  const Mesh box = make_box(2, 2, 2, 1);
  Vertices V(box.V.rows() + 1, 3);
  V << box.V, Eigen::RowVector3d(1e9, 0, 0);
  EXPECT_EQ(volume_reference(V, box.F), VolumeReference::Zero());
  V.row(0) = Eigen::RowVector3d::Constant(std::nan(""));
  EXPECT_TRUE(volume_reference(V, box.F).allFinite());
  EXPECT_EQ(volume_reference(V, Faces(0, 3)), VolumeReference::Zero());
}

// A model far from the origin (docs/method.md section 5): summed about its own reference point, its volume, the
// volume's gradient and the restoring cubic are those at the origin but for the rounding of the moved coordinates
// (1e-16 of the offset, relative to a unit radius). Summed about the origin, every term is about offset^3 for a
// volume of 4: at 1e5 the sum kept two digits.
TEST(Volume, AModelFarFromTheOriginKeepsItsDigits) {
  const Mesh s = make_icosphere(3, 1.0);
  const Vertices D = random_directions(s.V.rows(), 3);
  const double v0 = signed_volume(s.V, s.F);
  const Vertices G0 = volume_gradient(s.V, s.F);
  const std::array<double, 4> k0 = volume_along(s.V, D, s.F, volume_reference(s.V, s.F));
  for (double offset : {1e3, 1e5, 1e6}) {
    const Mesh far = test::translated(s, Eigen::RowVector3d(offset, -0.6 * offset, 0.3 * offset));
    const double tolerance = 1e-14 * offset;  // 1e-9 at 1e5
    EXPECT_NEAR(signed_volume(far.V, far.F), v0, tolerance * v0) << offset;
    EXPECT_LE((volume_gradient(far.V, far.F) - G0).norm(), tolerance * G0.norm()) << offset;
    const std::array<double, 4> k = volume_along(far.V, D, far.F, volume_reference(far.V, far.F));
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(k[i], k0[i], tolerance * v0) << offset << ", coefficient " << i;
  }
  const Mesh far = test::translated(s, Eigen::RowVector3d::Constant(1e5));
  EXPECT_GT(std::abs(signed_volume(far.V, far.F, VolumeReference::Zero()) - v0), 1e-6 * v0)
      << "about the origin the digits are lost (why the reference point exists)";
}

}  // namespace
}  // namespace sd
