#include "core/solver/internal/reduced/rotation_clusters.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <type_traits>
#include <utility>

#include "core/parallel/parallel_for.h"
#include "core/solver/internal/two_lane_kernels.h"
#include "core/solver/internal/energy/laplacian_basis_rows.h"
#include "core/solver/internal/reduced/training_poses.h"

namespace sd {
namespace {

// Clusters per task of a product (at least): a few hundred microseconds of work.
constexpr int kClusterBlock = 64;
// rotation_terms(): clusters whose 6 rows each are stacked per dense product, and the width of the column blocks
// (of the upper triangle) that the threads share.
constexpr Eigen::Index kTermsChunk = 128;
constexpr int kTermsColumns = 48;

// [w]x, the cross-product matrix: [w]x v = w x v.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& w) {
  Eigen::Matrix3d c;
  c << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return c;
}
// vee(Y - Y^T) for a 3x3 Y: the w with [w]x = Y - Y^T.
Eigen::Vector3d vee_of_skew(const Eigen::Matrix3d& Y) {
  return {Y(2, 1) - Y(1, 2), Y(0, 2) - Y(2, 0), Y(1, 0) - Y(0, 1)};
}

// The best rotation R of A and how it answers a change of A, (tr(S) I - S)^-1 for S = R A, from one SVD: with
// A = U Sigma V^T and R = V diag(1, 1, d) U^T (d = det(V U^T)), S = V diag(s) V^T with s = (sigma_1, sigma_2,
// d sigma_3), so tr(S) I - S has the eigenvalues sum(s) - s_i along V's columns: sums of two singular values. Where
// a one-ring is flattened to a line two of them vanish; below 1e-6 of the largest, the rotation about that line is
// held (the inverse's eigenvalue 0) instead of turning without bound.
struct TurnOfRing {
  Eigen::Matrix3d R, response;
};
TurnOfRing turn_of_ring(const Eigen::Matrix3d& A) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const double d = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  const Eigen::Vector3d s(svd.singularValues()[0], svd.singularValues()[1], d * svd.singularValues()[2]);
  const Eigen::Vector3d h = Eigen::Vector3d::Constant(s.sum()) - s;
  const double floor = 1e-6 * std::max(h.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  Eigen::Vector3d inverse;
  for (int k = 0; k < 3; ++k) inverse[k] = h[k] > floor ? 1.0 / h[k] : 0.0;
  const Eigen::Matrix3d& V = svd.matrixV();
  return {V * Eigen::Vector3d(1.0, 1.0, d).asDiagonal() * svd.matrixU().transpose(),
          V * inverse.asDiagonal() * V.transpose()};
}

Eigen::Matrix3d block_of(const Eigen::MatrixXd& M, Eigen::Index c) { return M.middleRows(3 * c, 3); }

// Clusters per task: fixed by the count alone, so that sums over the blocks are the same with any number of threads.
int cluster_block(Eigen::Index k) { return std::max(kClusterBlock, static_cast<int>((k + 15) / 16)); }

// The sum over k clusters of what add(c, part) adds into a rows x cols matrix: each fixed block of clusters sums
// into its own, and the blocks' matrices are added in block order (the same with any number of threads).
template <typename Add>
Eigen::MatrixXd sum_over_clusters(Eigen::Index k, Eigen::Index rows, Eigen::Index cols, Add&& add) {
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(rows, cols);
  return parallel::parallel_reduce(
      0, static_cast<int>(k), cluster_block(k), zero,
      [&](int lo, int hi) {
        Eigen::MatrixXd part = zero;
        for (Eigen::Index c = lo; c < hi; ++c) add(c, part);
        return part;
      },
      [](Eigen::MatrixXd a, const Eigen::MatrixXd& b) {
        a += b;
        return a;
      });
}

}  // namespace

Eigen::Matrix3d best_rotation(const Eigen::Matrix3d& A) { return turn_of_ring(A).R; }

VertexClusters farthest_point_clusters(const Vertices& X0, int k) {
  const Eigen::Index n = X0.rows();
  VertexClusters out{{}, std::vector<int>(static_cast<size_t>(n), 0)};
  Eigen::VectorXd distance = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  Eigen::Index sample = 0;
  for (int c = 0; c < k && c < n; ++c) {
    out.samples.push_back(static_cast<int>(sample));
    for (Eigen::Index i = 0; i < n; ++i) {
      const double d = (X0.row(i) - X0.row(sample)).squaredNorm();
      if (d < distance[i]) {
        distance[i] = d;
        out.owner[static_cast<size_t>(i)] = c;
      }
    }
    distance.maxCoeff(&sample);
  }
  return out;
}

VertexClusters surface_clusters(const Vertices& X0, const LaplacianCoordinates& rings, int k) {
  VertexClusters out{farthest_point_clusters(X0, k).samples, std::vector<int>(static_cast<size_t>(X0.rows()), -1)};
  // Multi-source Dijkstra along the edges from every sample at once: the lower distance wins, a tie whichever reached
  // the vertex first in the queue's order (distance, then vertex), so the clusters depend on the mesh alone.
  std::vector<double> distance(static_cast<size_t>(X0.rows()), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  auto seed = [&](int v, int cluster) {
    out.owner[static_cast<size_t>(v)] = cluster;
    distance[static_cast<size_t>(v)] = 0;
    queue.push({0.0, v});
  };
  auto grow = [&] {
    while (!queue.empty()) {
      const auto [d, v] = queue.top();
      queue.pop();
      if (d > distance[static_cast<size_t>(v)]) continue;
      for (int j : rings.one_ring(v)) {
        const double next = d + (X0.row(j) - X0.row(v)).norm();
        if (next < distance[static_cast<size_t>(j)]) {
          distance[static_cast<size_t>(j)] = next;
          out.owner[static_cast<size_t>(j)] = out.owner[static_cast<size_t>(v)];
          queue.push({next, j});
        }
      }
    }
  };
  for (size_t c = 0; c < out.samples.size(); ++c) seed(out.samples[c], static_cast<int>(c));
  grow();
  for (size_t v = 0; v < out.owner.size(); ++v)
    if (out.owner[v] < 0) {  // a component no sample reached
      out.samples.push_back(static_cast<int>(v));
      seed(static_cast<int>(v), static_cast<int>(out.samples.size()) - 1);
      grow();
    }
  return out;
}

RotationClusters::RotationClusters(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                                   const Eigen::MatrixXd& B, const VertexClusters& clusters,
                                   const std::vector<int>& left_out)
    : clusters_(clusters), B_(&B) {
  Eigen::MatrixXd rest_image;
  W.multiply(U0, rest_image);
  const Vertices Xbar = energy.rest_positions() - rest_image;  // X = Xbar + W U (Xbar ~ 0 for a cage's W)
  const Eigen::SparseMatrix<double>& SL = energy.laplacian();
  const Eigen::MatrixXd SL_Xbar = SL * Xbar;
  W.multiply_transpose(SL.transpose() * SL_Xbar, b0_);
  const Vertices delta = energy.coordinates().evaluate(energy.rest_positions());
  constant_ = 0.5 * (SL_Xbar.squaredNorm() + delta.squaredNorm());
  build_cross_terms(energy, W, delta, SL_Xbar, left_out);
  build_rings(energy, W, Xbar);
  linearize(U0);
}

void RotationClusters::build_cross_terms(const DeformationEnergy& energy, const BasisMatrix& W, const Vertices& delta,
                                         const Eigen::MatrixXd& SL_Xbar, const std::vector<int>& left_out) {
  const Eigen::Index k = sample_count(), m = W.cols();
  D_ = Rows::Zero(3 * k, m);
  e_ = Eigen::MatrixXd::Zero(3 * k, 3);
  K_ = Eigen::MatrixXd::Zero(3 * k, 3);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> SL = energy.laplacian();
  const std::vector<std::vector<int>> members = cluster_members(left_out);
  // Cluster by cluster in parallel (each cluster's rows are its task's alone), each summing its vertices in
  // increasing order: the same bits with any number of threads. The boy's 40k vertices took 0.25-0.4 s on one.
  parallel::parallel_for(0, static_cast<int>(k), 1, [&](int lo, int hi) {
    Eigen::RowVectorXd slw(m);  // (S L W)_i
    for (int c = lo; c < hi; ++c)
      for (int i : members[static_cast<size_t>(c)]) {
        slw.setZero();
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(SL, i); it; ++it)
          add_scaled_row(W, static_cast<int>(it.col()), it.value(), slw.data());
        const Eigen::Vector3d d = delta.row(i).transpose();
        D_.middleRows(3 * c, 3).noalias() += d * slw;
        e_.middleRows(3 * c, 3).noalias() += d * SL_Xbar.row(i);
        K_.middleRows(3 * c, 3) += d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose();
      }
  });
}

std::vector<std::vector<int>> RotationClusters::cluster_members(const std::vector<int>& left_out) const {
  std::vector<std::vector<int>> members(clusters_.samples.size());
  for (size_t i = 0; i < clusters_.owner.size(); ++i)
    if (!std::binary_search(left_out.begin(), left_out.end(), static_cast<int>(i)))
      members[static_cast<size_t>(clusters_.owner[i])].push_back(static_cast<int>(i));
  return members;
}

void RotationClusters::build_rings(const DeformationEnergy& energy, const BasisMatrix& W, const Vertices& Xbar) {
  const Eigen::Index k = sample_count(), m = W.cols();
  const Vertices& X0 = energy.rest_positions();
  Z_ = Rows::Zero(3 * k, m);
  a_ = Eigen::MatrixXd::Zero(3 * k, 3);
  Eigen::RowVectorXd edge(m);  // w_j - w_s
  for (Eigen::Index c = 0; c < k; ++c) {
    const int s = clusters_.samples[static_cast<size_t>(c)];
    for (int j : energy.coordinates().one_ring(s)) {
      const Eigen::Vector3d p = (X0.row(j) - X0.row(s)).transpose();
      edge.setZero();
      add_scaled_row(W, j, 1.0, edge.data());
      add_scaled_row(W, s, -1.0, edge.data());
      Z_.middleRows(3 * c, 3).noalias() += p * edge;
      a_.middleRows(3 * c, 3).noalias() += p * (Xbar.row(j) - Xbar.row(s));
    }
  }
}

Eigen::Matrix3d RotationClusters::times_unknowns(const Rows& rows, Eigen::Index c, const Eigen::MatrixXd& U) const {
  return two_lane::rows_times(rows.data() + 3 * c * rows.cols(), rows.cols(), U.data(), U.rows());
}

double RotationClusters::energy(const Eigen::MatrixXd& U) const {
  // The cross term cluster by cluster (a 3 x 3 SVD each), in the threads' fixed blocks. Each cluster's turn is kept
  // for linearize(): the line search's last evaluation is the next step's point.
  const Eigen::Index k = sample_count();
  evaluated_.resize(k);
  const double cross = parallel::parallel_sum(0, static_cast<int>(k), cluster_block(k), [&](int lo, int hi) {
    double sum = 0;
    for (Eigen::Index c = lo; c < hi; ++c) {
      ClusterTurn& turn = evaluated_.turn(c);
      turn_cluster(c, U, turn);
      sum += turn.P.trace();
    }
    return sum;
  });
  evaluated_.U = U;
  return 0.5 * U.cwiseProduct(two_lane::matrix_times_block(*B_, U)).sum() + U.cwiseProduct(b0_).sum() + constant_ -
         cross;
}

void RotationClusters::evaluate(const Eigen::MatrixXd& U, EnergyEvaluation& e) const { e.laplacian_energy = energy(U); }

void RotationClusters::turn_cluster(Eigen::Index c, const Eigen::MatrixXd& U, ClusterTurn& out) const {
  const TurnOfRing turn = turn_of_ring(block_of(a_, c) + times_unknowns(Z_, c, U));
  out.R = turn.R;
  out.response = turn.response;
  out.P = turn.R * (times_unknowns(D_, c, U) + block_of(e_, c));
}

void RotationClusters::linearize(const Eigen::MatrixXd& U) {
  const Eigen::Index k = sample_count();
  // At the point energy() last evaluated (compared by value), its turns are this point's: the same bits, no SVD.
  const bool evaluated =
      evaluated_.size() == k && evaluated_.U.rows() == U.rows() && evaluated_.U.cols() == U.cols() && evaluated_.U == U;
  U_ = U;
  R_.resize(3 * k, 3);
  T_.resize(3 * k, Z_.cols());
  Hinv_.resize(3 * k, 3);
  P_.resize(3 * k, 3);
  parallel::parallel_for(0, static_cast<int>(k), cluster_block(k), [&](int lo, int hi) {
    ClusterTurn made;
    for (Eigen::Index c = lo; c < hi; ++c) {
      const ClusterTurn& turn = evaluated ? evaluated_.turn(c) : made;
      if (!evaluated) turn_cluster(c, U, made);
      R_.middleRows(3 * c, 3) = turn.R;
      T_.middleRows(3 * c, 3).noalias() = turn.R * Z_.middleRows(3 * c, 3);
      Hinv_.middleRows(3 * c, 3) = turn.response;
      P_.middleRows(3 * c, 3) = turn.P;
    }
  });
}

Eigen::MatrixXd RotationClusters::gradient(const EnergyEvaluation&) const {
  // B U + b0 - sum_c (D_c^T R_c^T + G_c^T g_c), g_c = vee(P_c^T - P_c) the cross term's pull on the rotation,
  // G_c^T y = -T_c^T [H_c^-1 y]x (the rotation's derivative, transposed).
  const Eigen::Index m = U_.rows();
  Eigen::MatrixXd out = sum_over_clusters(sample_count(), m, 3, [&](Eigen::Index c, Eigen::MatrixXd& part) {
    const Eigen::Matrix3d pull = cross_matrix(block_of(Hinv_, c) * -vee_of_skew(block_of(P_, c)));
    two_lane::add_rows_transpose_times(D_.data() + 3 * c * m, m, -block_of(R_, c).transpose(), part.data(), m);
    two_lane::add_rows_transpose_times(T_.data() + 3 * c * m, m, pull, part.data(), m);
  });
  out += two_lane::matrix_times_block(*B_, U_) + b0_;
  return out;
}

Eigen::MatrixXd RotationClusters::product(const Eigen::MatrixXd& V) const {
  // J_i V = (S L W)_i V + [R_c delta_i]x w_c with w_c = G_c V = H_c^-1 vee(X^T - X), X = T_c V; summed per cluster,
  // J^T J V = B V + D_c^T (R_c^T [w_c]x) - T_c^T [H_c^-1 (vee(Q - Q^T) + R_c K_c R_c^T w_c)]x with Q = R_c D_c V.
  // Cluster by cluster, so that D_c and T_c are read once and in cache; fixed blocks of clusters, so that the sum
  // is the same with any number of threads.
  const Eigen::Index m = V.rows();
  Eigen::MatrixXd out = sum_over_clusters(sample_count(), m, V.cols(), [&](Eigen::Index c, Eigen::MatrixXd& part) {
    const double* Dc = D_.data() + 3 * c * m;
    const double* Tc = T_.data() + 3 * c * m;
    const Eigen::Matrix3d R = block_of(R_, c), Hinv = block_of(Hinv_, c);
    const Eigen::Matrix3d turned_K = R * block_of(K_, c) * R.transpose();
    for (Eigen::Index t = 0; t < V.cols() / 3; ++t) {
      const double* Vt = V.data() + 3 * t * m;
      const Eigen::Matrix3d DV = two_lane::rows_times(Dc, m, Vt, m);
      const Eigen::Matrix3d TV = two_lane::rows_times(Tc, m, Vt, m);
      const Eigen::Vector3d w = Hinv * -vee_of_skew(TV);
      const Eigen::Vector3d y = vee_of_skew(R * DV) + turned_K * w;
      double* out_t = part.data() + 3 * t * m;
      two_lane::add_rows_transpose_times(Dc, m, R.transpose() * cross_matrix(w), out_t, m);
      two_lane::add_rows_transpose_times(Tc, m, -cross_matrix(Hinv * y), out_t, m);
    }
  });
  out += two_lane::matrix_times_block(*B_, V);
  return out;
}

Eigen::MatrixXd RotationClusters::dense_matrix() const {
  Eigen::MatrixXd A = rotation_terms();
  const Eigen::Index m = B_->rows();
  for (Eigen::Index axis = 0; axis < 3; ++axis) A.block(axis * m, axis * m, m, m) += *B_;
  return A;
}

Eigen::MatrixXd RotationClusters::rotation_terms(bool single_precision) const {
  return single_precision ? summed_terms<float>() : summed_terms<double>();
}

template <typename Scalar>
Eigen::MatrixXd RotationClusters::summed_terms() const {
  // The matrix that product() applies, beyond B V: with G_c = -H_c^-1 Phi(T_c) (the rotation's response, w_c = G_c V)
  // and F_c = Phi(R_c D_c), cluster c adds F^T G + G^T F + G^T Q G (Q = R_c K_c R_c^T) = Y^T M Y for the 6 rows
  // Y = [G; F] and M = [[Q, I], [I, 0]]. Axis b's columns of G and F are -H^-1 [e_b]x T_c and [e_b]x R_c D_c, as
  // Phi(X) V = vee(X V - (X V)^T) = sum_b [e_b]x X V_b.
  // Chunks of clusters are stacked and Y^T (M Y) added by column blocks of the upper triangle in parallel: each entry
  // is summed by one task, chunk after chunk, so that the matrix is the same with any number of threads.
  const Eigen::Index k = sample_count(), m = Z_.cols(), n = 3 * m;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n);
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  Matrix Y(6 * std::min(k, kTermsChunk), n), MY(Y.rows(), n);
  for (Eigen::Index first = 0; first < k; first += kTermsChunk) {
    const Eigen::Index count = std::min(kTermsChunk, k - first);
    for (Eigen::Index t = 0; t < count; ++t) {
      const Eigen::Index c = first + t;
      const Eigen::Matrix3d R = block_of(R_, c), Hinv = block_of(Hinv_, c);
      const Eigen::Matrix3d Q = R * block_of(K_, c) * R.transpose();
      const Eigen::Matrix<double, 3, Eigen::Dynamic> RD = R * D_.middleRows(3 * c, 3);
      for (int b = 0; b < 3; ++b) {
        const Eigen::Matrix3d axis = cross_matrix(Eigen::Vector3d::Unit(b));
        const Eigen::Matrix<double, 3, Eigen::Dynamic> G = -Hinv * axis * T_.middleRows(3 * c, 3);
        const Eigen::Matrix<double, 3, Eigen::Dynamic> F = axis * RD;
        Y.block(6 * t, b * m, 3, m) = G.cast<Scalar>();
        Y.block(6 * t + 3, b * m, 3, m) = F.cast<Scalar>();
        MY.block(6 * t, b * m, 3, m) = (Q * G + F).cast<Scalar>();
        MY.block(6 * t + 3, b * m, 3, m) = G.cast<Scalar>();
      }
    }
    const Eigen::Index rows = 6 * count;
    const int blocks = static_cast<int>((n + kTermsColumns - 1) / kTermsColumns);
    parallel::parallel_for(0, blocks, 1, [&](int lo, int hi) {
      for (int j = lo; j < hi; ++j) {
        const Eigen::Index j0 = static_cast<Eigen::Index>(j) * kTermsColumns;
        const Eigen::Index width = std::min<Eigen::Index>(kTermsColumns, n - j0);
        if constexpr (std::is_same_v<Scalar, double>) {
          out.block(0, j0, j0 + width, width).noalias() +=
              Y.topLeftCorner(rows, j0 + width).transpose() * MY.block(0, j0, rows, width);
        } else {
          const Matrix part = Y.topLeftCorner(rows, j0 + width).transpose() * MY.block(0, j0, rows, width);
          out.block(0, j0, j0 + width, width) += part.template cast<double>();
        }
      }
    });
  }
  out.triangularView<Eigen::StrictlyLower>() = out.transpose();
  return out;
}

double cluster_test_error(RotationClusters& rule, const DeformationEnergy& energy, const BasisMatrix& W,
                          const Eigen::MatrixXd& U0, int poses, unsigned seed) {
  std::vector<double> errors;
  for (const Eigen::MatrixXd& U : training_poses(energy.rest_positions(), W, U0, poses, seed)) {
    Eigen::MatrixXd image, full;
    W.multiply(U - U0, image);
    const Vertices X = energy.rest_positions() + image;
    const EnergyEvaluation e = energy.evaluate(X);
    W.multiply_transpose(energy.jacobian(X).laplacian_rows_transpose(e.laplacian_residual), full);
    rule.linearize(U);
    const double cross = (rule.squares_gradient(U) - full).norm();
    errors.push_back(cross > 0 ? (rule.gradient(e) - full).norm() / cross : 0.0);
  }
  if (errors.empty()) return 0.0;
  std::sort(errors.begin(), errors.end());
  const size_t half = errors.size() / 2;
  return errors.size() % 2 ? errors[half] : 0.5 * (errors[half - 1] + errors[half]);
}

}  // namespace sd
