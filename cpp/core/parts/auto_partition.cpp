#include "core/parts/auto_partition.h"

#include <algorithm>
#include <limits>
#include <random>
#include <string>

#include "core/error.h"
#include "core/mesh/laplacian_eigenpairs.h"
#include "core/parts/partition.h"

namespace sd {
namespace {

constexpr int kRestarts = 8;
constexpr int kMaxLloydIterations = 200;
constexpr unsigned kSeed = 1;

// Rows: vertices; columns: phi_j / sqrt(lambda_j) for j = 1 .. d (the constant phi_0 left out).
Eigen::MatrixXd embedding(const Eigenpairs& pairs) {
  const Eigen::Index d = pairs.values.size() - 1;
  Eigen::MatrixXd Y(pairs.vectors.rows(), d);
  for (Eigen::Index j = 0; j < d; ++j)
    Y.col(j) = pairs.vectors.col(j + 1) / std::sqrt(std::max(pairs.values[j + 1], 1e-300));
  return Y;
}

struct Clustering {
  std::vector<int> label;
  double cost = std::numeric_limits<double>::infinity();
};

constexpr Eigen::Index kAssignBlock = 2048;  // rows per product: an n by K distance matrix could be gigabytes

// Gives every row of Y its nearest centre (the first on a tie), adding w_i |y_i - c|^2 to c.cost; true when a label
// changed. The squared distances |y|^2 - 2 y.c + |c|^2 come from one matrix product per block of rows: the
// assignment is where k-means spends its time (n K d per Lloyd iteration), and as a product it runs at the speed
// of a matrix multiplication instead of row by row (K = 50 on a 10k-vertex sphere took 100 s before).
bool assign(const Eigen::MatrixXd& Y, const Eigen::VectorXd& y2, const Eigen::VectorXd& w,
            const Eigen::MatrixXd& centres, Clustering& c) {
  const Eigen::RowVectorXd c2 = centres.rowwise().squaredNorm().transpose();
  bool changed = false;
  for (Eigen::Index start = 0; start < Y.rows(); start += kAssignBlock) {
    const Eigen::Index rows = std::min(kAssignBlock, Y.rows() - start);
    Eigen::MatrixXd d2 = -2.0 * (Y.middleRows(start, rows) * centres.transpose());
    d2.rowwise() += c2;
    for (Eigen::Index r = 0; r < rows; ++r) {
      const Eigen::Index i = start + r;
      Eigen::Index best = 0;
      const double nearest = std::max(d2.row(r).minCoeff(&best) + y2[i], 0.0);  // rounding may dip below 0
      c.cost += w[i] * nearest;
      if (c.label[static_cast<size_t>(i)] != best) {
        c.label[static_cast<size_t>(i)] = static_cast<int>(best);
        changed = true;
      }
    }
  }
  return changed;
}

// Weighted k-means++ seeding, then Lloyd until no label changes.
Clustering kmeans(const Eigen::MatrixXd& Y, const Eigen::VectorXd& w, int K, std::mt19937& rng) {
  const Eigen::Index n = Y.rows();
  Eigen::MatrixXd centres(K, Y.cols());
  Eigen::VectorXd nearest = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  const auto pick = [&](const Eigen::VectorXd& weight) {
    std::uniform_real_distribution<double> u(0.0, weight.sum());
    double target = u(rng);
    for (Eigen::Index i = 0; i < n; ++i)
      if ((target -= weight[i]) <= 0.0) return i;
    return n - 1;
  };
  for (int k = 0; k < K; ++k) {
    const Eigen::Index i = k == 0 ? pick(w) : pick(w.cwiseProduct(nearest));
    centres.row(k) = Y.row(i);
    nearest = nearest.cwiseMin((Y.rowwise() - centres.row(k)).rowwise().squaredNorm());
  }
  Clustering c;
  c.label.assign(static_cast<size_t>(n), -1);
  const Eigen::VectorXd y2 = Y.rowwise().squaredNorm();
  for (int it = 0; it < kMaxLloydIterations; ++it) {
    c.cost = 0.0;
    const bool changed = assign(Y, y2, w, centres, c);
    if (!changed) break;
    Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(K, Y.cols());
    Eigen::VectorXd mass = Eigen::VectorXd::Zero(K);
    for (Eigen::Index i = 0; i < n; ++i) {
      sums.row(c.label[i]) += w[i] * Y.row(i);
      mass[c.label[i]] += w[i];
    }
    for (int k = 0; k < K; ++k)
      if (mass[k] > 0.0) centres.row(k) = sums.row(k) / mass[k];
  }
  return c;
}

}  // namespace

std::vector<int> auto_parts(const Mesh& mesh, int K) {
  const int n = static_cast<int>(mesh.V.rows());
  // K + 3 eigenpairs are needed; written without K + 3, which overflows for K near INT_MAX.
  const int most = std::min(std::max(n - 4, 0), kMaxVolumeParts);
  if (n < 5)  // counted after welding, which a file's vertex count can hide
    throw Error("volume parts: the automatic partition needs a mesh of at least 5 vertices; this one has " +
                std::to_string(n) + " distinct points");
  if (K < 1 || K > most)
    throw Error("volume parts: the automatic partition needs from 1 to " + std::to_string(most) +
                " parts for this mesh of " + std::to_string(n) + " vertices (at most " +
                std::to_string(kMaxVolumeParts) + " for any mesh); got " + std::to_string(K));
  if (K == 1) return std::vector<int>(static_cast<size_t>(mesh.F.rows()), 0);
  EigenpairOptions options;
  options.count = K + 3;  // the constant and d = K + 2 modes
  const Eigenpairs pairs = laplacian_eigenpairs(mesh.V, mesh.F, options);
  const Eigen::MatrixXd Y = embedding(pairs);
  std::mt19937 rng(kSeed);
  Clustering best;
  for (int r = 0; r < kRestarts; ++r) {
    Clustering c = kmeans(Y, pairs.mass, K, rng);
    if (c.cost < best.cost) best = std::move(c);
  }
  std::vector<int> part = parts_from_vertex_labels(best.label, mesh.F);
  connect_parts(part, mesh.F);
  compact_parts(part);
  return part;
}

}  // namespace sd
