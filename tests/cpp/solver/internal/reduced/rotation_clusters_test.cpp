// The rotation-cluster rule (rotation_clusters.h) against a plain per-vertex implementation of the same energy:
// its algebra (the value without vertices equals the sum over them), its derivatives against finite differences,
// the rest pose, and the rule's test error against the full term.
#include "core/solver/internal/reduced/rotation_clusters.h"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <iostream>

#include "core/basis/mean_value_coordinates.h"
#include "core/mesh/examples.h"
#include "core/parallel/thread_pool.h"
#include "core/solver/internal/reduced/training_poses.h"
#include "core/solver/internal/steps/subspace_step.h"
#include "test_support.h"

namespace sd {
namespace {

// The cage's vertices moved by up to `size` at random (a basis whose rest unknowns do not reproduce the rest mesh).
Eigen::MatrixXd moved(const Eigen::MatrixXd& U, double size, unsigned seed) {
  Eigen::MatrixXd out = U;
  PortableRandom random(seed);
  for (Eigen::Index k = 0; k < out.size(); ++k) out.data()[k] += random.uniform(-size, size);
  return out;
}

// The bar in its cage with 40 clusters (so that each holds many vertices and the rule is an approximation). With
// an offset, the rest unknowns U0 are the cage moved at random, so X = X0 + W (U - U0) has Xbar = X0 - W U0 != 0 (as
// the spectral basis has) and the rule's constant parts (b0, c0, e_c, a_c) matter.
struct ClusterPieces {
  explicit ClusterPieces(double offset = 0.0, int count = 40) : count(count), rest(moved(bar.cage.V, offset, 11)) {}
  int count;  // clusters
  Example bar = make_example("bar");
  DeformationEnergy energy{bar.mesh.V, bar.mesh.F};
  BasisMatrix W = mean_value_coordinates(bar.mesh.V, bar.cage);
  SubspaceStep subspace{energy, W};
  VertexClusters clusters = surface_clusters(bar.mesh.V, energy.coordinates(), count);
  Eigen::MatrixXd rest;
  RotationClusters rule{energy, W, rest, subspace.laplacian_gram(), clusters};
  Vertices delta = energy.coordinates().evaluate(bar.mesh.V);

  Vertices map(const Eigen::MatrixXd& U) const {
    Eigen::MatrixXd image;
    W.multiply(U - rest, image);
    return bar.mesh.V + image;
  }
  // r_i = (S L X)_i - R_c delta_i, vertex by vertex, R_c by Kabsch on the sample's one-ring (rest -> X).
  Eigen::VectorXd residual_at(const Eigen::MatrixXd& U) const {
    const Vertices X = map(U);
    const Vertices LX = energy.laplacian() * X;
    std::vector<Eigen::Matrix3d> R;
    for (int s : clusters.samples) {
      Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
      for (int j : energy.coordinates().one_ring(s))
        A += (bar.mesh.V.row(j) - bar.mesh.V.row(s)).transpose() * (X.row(j) - X.row(s));
      const Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
      Eigen::Matrix3d sign = Eigen::Matrix3d::Identity();
      if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0) sign(2, 2) = -1;
      R.push_back(svd.matrixV() * sign * svd.matrixU().transpose());
    }
    Eigen::VectorXd r(3 * X.rows());
    for (Eigen::Index i = 0; i < X.rows(); ++i)
      r.segment<3>(3 * i) = LX.row(i).transpose() -
                            R[static_cast<size_t>(clusters.owner[static_cast<size_t>(i)])] * delta.row(i).transpose();
    return r;
  }
  Eigen::MatrixXd perturbed(unsigned seed, double size = 0.1) const { return moved(rest, size, seed); }
};

TEST(RotationClusters, TheValueWithoutVerticesIsTheSumOverThem) {
  for (double offset : {0.0, 0.05}) {
    ClusterPieces p(offset);
    for (unsigned seed : {1u, 2u, 3u}) {
      const Eigen::MatrixXd U = p.perturbed(seed, 0.05 * seed);
      const double direct = 0.5 * p.residual_at(U).squaredNorm();
      EXPECT_NEAR(p.rule.energy(U), direct, 1e-10 * direct) << "offset " << offset << ", seed " << seed;
    }
  }
}

TEST(RotationClusters, GradientMatchesFiniteDifferences) {
  for (double offset : {0.0, 0.05}) {
    ClusterPieces p(offset);
    const Eigen::MatrixXd U = p.perturbed(4);
    p.rule.linearize(U);
    const Eigen::MatrixXd g = p.rule.gradient(EnergyEvaluation());
    EXPECT_LE(test::gradient_error(U, g, [&](const Eigen::MatrixXd& V) { return p.rule.energy(V); }),
              1e-6 * g.cwiseAbs().maxCoeff())
        << "offset " << offset;
  }
}

// linearize() takes the turns energy() made at the same point instead of making them again: the same bits as a
// linearisation from scratch, and one at another point than the last evaluated makes its own.
TEST(RotationClusters, LinearizingWhereTheEnergyWasEvaluatedGivesTheSameBits) {
  ClusterPieces p(0.05);
  const Eigen::MatrixXd U = p.perturbed(5), other = p.perturbed(6), V = p.perturbed(7) - p.rest;
  const auto linearized = [&](const Eigen::MatrixXd& at) {
    p.rule.linearize(at);
    Eigen::MatrixXd out(V.rows(), 6);
    out << p.rule.gradient(EnergyEvaluation()), p.rule.product(V);
    return out;
  };
  p.rule.energy(other);
  const Eigen::MatrixXd fresh = linearized(U);  // U was not the last point evaluated
  p.rule.energy(U);
  const Eigen::MatrixXd kept = linearized(U);
  EXPECT_EQ((kept - fresh).cwiseAbs().maxCoeff(), 0.0);
  p.rule.energy(U);
  const Eigen::MatrixXd elsewhere = linearized(other);  // another point than the evaluated one
  p.rule.energy(other);
  EXPECT_EQ((linearized(other) - elsewhere).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT((elsewhere - fresh).cwiseAbs().maxCoeff(), 0.0);
}

// A pose that mirrors the bar turns every cluster's best rotation through Kabsch's reflection branch: the value and
// gradient still match the per-vertex sum and its differences.
TEST(RotationClusters, MirroredPoseTakesTheProperRotations) {
  ClusterPieces p;
  Eigen::MatrixXd U = p.rest;
  U.col(0) *= -1.0;
  U = moved(U, 0.02, 9);
  const double direct = 0.5 * p.residual_at(U).squaredNorm();
  EXPECT_NEAR(p.rule.energy(U), direct, 1e-10 * direct);
  p.rule.linearize(U);
  const Eigen::MatrixXd g = p.rule.gradient(EnergyEvaluation());
  EXPECT_LE(test::gradient_error(U, g, [&](const Eigen::MatrixXd& V) { return p.rule.energy(V); }),
            1e-6 * g.cwiseAbs().maxCoeff());
}

// Two copies of the bar side by side, closer to each other than a cluster is wide: clusters along the surface never
// span both, and a copy no sample reaches gets its own.
TEST(RotationClusters, SurfaceClustersStayInTheirComponent) {
  const Example bar = make_example("bar");
  const Eigen::Index n = bar.mesh.V.rows();
  const double height = bar.mesh.V.col(1).maxCoeff() - bar.mesh.V.col(1).minCoeff();
  Mesh two;
  two.V.resize(2 * n, 3);
  two.V << bar.mesh.V, bar.mesh.V.rowwise() + Eigen::RowVector3d(0, 1.05 * height, 0);
  two.F.resize(2 * bar.mesh.F.rows(), 3);
  two.F << bar.mesh.F, bar.mesh.F.array() + static_cast<int>(n);
  const DeformationEnergy energy(two.V, two.F);
  for (int k : {1, 20}) {
    const VertexClusters c = surface_clusters(two.V, energy.coordinates(), k);
    EXPECT_GE(static_cast<int>(c.samples.size()), std::max(k, 2)) << k;
    for (Eigen::Index i = 0; i < 2 * n; ++i) {
      const int sample = c.samples[static_cast<size_t>(c.owner[static_cast<size_t>(i)])];
      EXPECT_EQ(i < n, sample < n) << "vertex " << i << " with sample " << sample << " (" << k << " clusters)";
    }
  }
  // In space, the nearest sample of some vertices lies on the other copy.
  const VertexClusters in_space = farthest_point_clusters(two.V, 20);
  int crossing = 0;
  for (Eigen::Index i = 0; i < 2 * n; ++i)
    crossing += (i < n) != (in_space.samples[static_cast<size_t>(in_space.owner[static_cast<size_t>(i)])] < n);
  EXPECT_GT(crossing, 0);
}

// The Gauss-Newton matrix is J^T J for the Jacobian of the per-vertex residual by central differences; the
// matrix-free product applies it.
TEST(RotationClusters, GaussNewtonMatrixIsJacobianTransposeJacobian) {
  ClusterPieces p;
  const Eigen::MatrixXd U = p.perturbed(5);
  p.rule.linearize(U);
  const Eigen::MatrixXd J = test::central_differences(U, [&](const Eigen::MatrixXd& V) { return p.residual_at(V); });
  const Eigen::MatrixXd expected = J.transpose() * J, A = p.rule.dense_matrix();
  EXPECT_LE((A - expected).cwiseAbs().maxCoeff(), 1e-6 * expected.cwiseAbs().maxCoeff());
  const Eigen::MatrixXd V = p.perturbed(6) - p.rest;
  const Eigen::MatrixXd AV = p.rule.product(V);
  const Eigen::VectorXd dense = A * Eigen::Map<const Eigen::VectorXd>(V.data(), V.size());
  EXPECT_LE((Eigen::Map<const Eigen::VectorXd>(AV.data(), AV.size()) - dense).norm(), 1e-10 * dense.norm());
}

// Vertices left out (held exactly elsewhere, as the factor preconditioner's stiff vertices are) leave exactly their
// part of the rotation terms out: all vertices' terms less those without them equal J_L^T J_L - A_L^T A_L, from the
// left-out rows L of the residual's and of S L X's central-difference Jacobians.
TEST(RotationClusters, LeftOutVerticesLeaveTheirRotationTermsOut) {
  ClusterPieces p;
  std::vector<int> left_out;
  for (int i = 0; i < p.bar.mesh.V.rows(); i += 7) left_out.push_back(i);
  RotationClusters rest_only(p.energy, p.W, p.rest, p.subspace.laplacian_gram(), p.clusters, left_out);
  const Eigen::MatrixXd U = p.perturbed(5);
  p.rule.linearize(U);
  rest_only.linearize(U);
  const auto left_rows = [&](const Eigen::VectorXd& r) {
    Eigen::VectorXd out(3 * static_cast<Eigen::Index>(left_out.size()));
    for (size_t k = 0; k < left_out.size(); ++k)
      out.segment<3>(3 * static_cast<Eigen::Index>(k)) = r.segment<3>(3 * left_out[k]);
    return out;
  };
  const Eigen::MatrixXd J =
      test::central_differences(U, [&](const Eigen::MatrixXd& V) { return left_rows(p.residual_at(V)); });
  const Eigen::MatrixXd A = test::central_differences(U, [&](const Eigen::MatrixXd& V) {
    const Vertices LX = p.energy.laplacian() * p.map(V);  // row-major: x, y, z of each vertex in turn
    return left_rows(Eigen::Map<const Eigen::VectorXd>(LX.data(), LX.size()));
  });
  const Eigen::MatrixXd expected = J.transpose() * J - A.transpose() * A;
  const Eigen::MatrixXd got = p.rule.rotation_terms() - rest_only.rotation_terms();
  EXPECT_GT(expected.cwiseAbs().maxCoeff(), 1e-3 * p.rule.rotation_terms().cwiseAbs().maxCoeff());
  EXPECT_LE((got - expected).cwiseAbs().maxCoeff(), 1e-6 * expected.cwiseAbs().maxCoeff());
}

// With 300 clusters the dense sums run over three chunks of clusters and several column blocks: the matrix is still
// the one the products apply (column by column, to rounding), and the same bits with one thread and two.
TEST(RotationClusters, RotationTermsOverSeveralChunksAreTheProductsMatrix) {
  ClusterPieces p(0.0, 300);
  ASSERT_GE(p.rule.sample_count(), 300);
  p.rule.linearize(p.perturbed(8));
  const int saved = parallel::threads();
  parallel::set_threads(1);
  const Eigen::MatrixXd one = p.rule.dense_matrix();
  parallel::set_threads(2);
  const Eigen::MatrixXd two = p.rule.dense_matrix();
  parallel::set_threads(saved);
  EXPECT_EQ((one - two).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::Index m = p.W.cols();
  Eigen::MatrixXd units = Eigen::MatrixXd::Zero(m, 9 * m);  // column axis * m + j as one m by 3 block each
  for (Eigen::Index column = 0; column < 3 * m; ++column) units(column % m, 3 * column + column / m) = 1.0;
  const Eigen::MatrixXd images = p.rule.product(units);
  const Eigen::Map<const Eigen::MatrixXd> from_products(images.data(), 3 * m, 3 * m);
  EXPECT_LE((one - from_products).cwiseAbs().maxCoeff(), 1e-12 * one.cwiseAbs().maxCoeff());
}

TEST(RotationClusters, SinglePrecisionTermsAreTheDoubleOnesToFloatRounding) {
  // The factor preconditioner takes them in single precision: about 1e-7 of the largest entry off, and the same
  // with any number of threads.
  ClusterPieces p(0.0, 300);
  p.rule.linearize(p.perturbed(8));
  const Eigen::MatrixXd exact = p.rule.rotation_terms();
  const int saved = parallel::threads();
  parallel::set_threads(1);
  const Eigen::MatrixXd one = p.rule.rotation_terms(/*single_precision=*/true);
  parallel::set_threads(2);
  const Eigen::MatrixXd two = p.rule.rotation_terms(/*single_precision=*/true);
  parallel::set_threads(saved);
  const double largest = exact.cwiseAbs().maxCoeff();
  EXPECT_LE((one - exact).cwiseAbs().maxCoeff(), 1e-5 * largest);
  EXPECT_GT((one - exact).cwiseAbs().maxCoeff(), 0.0) << "computed in float indeed";
  EXPECT_EQ((one - two).cwiseAbs().maxCoeff(), 0.0);
}

TEST(RotationClusters, RestPoseIsAMinimumOfTheTerm) {
  ClusterPieces p;
  const Eigen::MatrixXd& U0 = p.rest;
  p.rule.linearize(U0);
  const double scale = p.delta.squaredNorm();
  EXPECT_LE(std::abs(p.rule.energy(U0)), 1e-12 * scale);
  EXPECT_LE(p.rule.gradient(EnergyEvaluation()).norm(), 1e-10 * std::sqrt(scale));
}

// The rule's gradient is near the full term's on held-out poses, and nearer with more clusters (the error is the
// cross term's only). The bar's 5,042 vertices in 640 clusters: under 2% of the cross term's gradient (the median
// over the poses; measured 0.7%).
TEST(RotationClusters, TestErrorIsSmallAndShrinksWithMoreClusters) {
  ClusterPieces p;
  double previous = 1.0;
  for (int k : {10, 40, 160, 640}) {
    RotationClusters rule(p.energy, p.W, p.bar.cage.V, p.subspace.laplacian_gram(),
                          surface_clusters(p.bar.mesh.V, p.energy.coordinates(), k));
    const double error = cluster_test_error(rule, p.energy, p.W, p.bar.cage.V, 4, 1);
    std::cout << "[          ] " << k << " clusters of " << p.bar.mesh.V.rows() << " vertices: test error " << error
              << "\n";
    EXPECT_LT(error, previous) << k << " clusters";
    previous = error;
  }
  EXPECT_LT(previous, 0.02);
}

}  // namespace
}  // namespace sd
