#include "core/solver/internal/reduced/cubature.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/solver/internal/energy/laplacian_coordinates.h"
#include "core/solver/internal/energy/laplacian_rows.h"
#include "core/solver/internal/reduced/nnls.h"
#include "core/solver/internal/reduced/training_poses.h"
#include "core/timer.h"

namespace sd {
namespace {

// Farthest-point sampling runs over at most this many vertices (a random subset of larger meshes): enough to
// spread a few hundred samples and to estimate their cells' areas.
constexpr int kSpreadPool = 50000;

// `count` distinct vertices drawn at random, increasing.
std::vector<int> random_vertices(int n, int count, PortableRandom& random) {
  std::vector<int> out;
  if (count >= n) {
    out.resize(n);
    std::iota(out.begin(), out.end(), 0);
    return out;
  }
  std::vector<char> taken(static_cast<size_t>(n), 0);
  while (static_cast<int>(out.size()) < count) {
    const int i = random.below(n);
    if (!taken[i]) {
      taken[i] = 1;
      out.push_back(i);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// `count` distinct vertices drawn at random among those not excluded, increasing (all of them when fewer).
std::vector<int> random_vertices_except(int n, int count, const std::vector<int>& excluded, PortableRandom& random) {
  if (excluded.empty()) return random_vertices(n, count, random);
  std::vector<char> out(static_cast<size_t>(n), 0);
  for (int i : excluded) out[static_cast<size_t>(i)] = 1;
  std::vector<int> rest;
  for (int i = 0; i < n; ++i)
    if (!out[static_cast<size_t>(i)]) rest.push_back(i);
  std::vector<int> picked = random_vertices(static_cast<int>(rest.size()), count, random);
  for (int& k : picked) k = rest[static_cast<size_t>(k)];
  return picked;
}

// Farthest-point sampling of `count` pool vertices (not in `exact`), with the quadrature weight of each: the area of
// the pool vertices nearest to it (scaled to the surface less the exact vertices) over its own area. The `exact`
// vertices are samples of weight 1: each integrates itself.
void spread_samples(const DeformationEnergy& energy, int count, const std::vector<int>& exact, PortableRandom& random,
                    std::vector<int>& samples, Eigen::VectorXd& weights) {
  const Vertices& X0 = energy.rest_positions();
  const Eigen::VectorXd& area = energy.weights().vertex_areas();
  const std::vector<int> pool = random_vertices_except(energy.vertex_count(), kSpreadPool, exact, random);
  const int P = static_cast<int>(pool.size());
  std::vector<double> distance(static_cast<size_t>(P), std::numeric_limits<double>::infinity());
  std::vector<int> owner(static_cast<size_t>(P), 0), picked{0};
  for (int k = 0; k < count; ++k) {
    const Eigen::RowVector3d p = X0.row(pool[picked[k]]);
    int farthest = 0;
    for (int i = 0; i < P; ++i) {
      const double d = (X0.row(pool[i]) - p).squaredNorm();
      if (d < distance[i]) {
        distance[i] = d;
        owner[i] = k;
      }
      if (distance[i] > distance[farthest]) farthest = i;
    }
    if (k + 1 < count) picked.push_back(farthest);
  }
  Eigen::VectorXd cell = Eigen::VectorXd::Zero(count);
  double pool_area = 0.0;
  for (int i = 0; i < P; ++i) {
    cell[owner[i]] += area[pool[i]];
    pool_area += area[pool[i]];
  }
  double exact_area = 0.0;
  for (int i : exact) exact_area += area[i];
  const double to_surface = (area.sum() - exact_area) / pool_area;
  std::vector<std::pair<int, double>> rule;  // (vertex, weight), sorted by vertex
  for (int k = 0; k < count; ++k) rule.emplace_back(pool[picked[k]], to_surface * cell[k] / area[pool[picked[k]]]);
  for (int i : exact) rule.emplace_back(i, 1.0);
  std::sort(rule.begin(), rule.end());
  samples.clear();
  weights.resize(static_cast<Eigen::Index>(rule.size()));
  for (size_t k = 0; k < rule.size(); ++k) {
    samples.push_back(rule[k].first);
    weights[static_cast<Eigen::Index>(k)] = rule[k].second;
  }
}

// The fit's columns (one per vertex of `vertices`) and target for a set of poses: per pose, the energy and its
// derivative along each direction Z_l, of each vertex's term (A) and summed over every vertex (b), the pose's rows
// scaled to unit size.
struct FitData {
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
};

FitData assemble(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                 const std::vector<Eigen::MatrixXd>& poses, const std::vector<int>& vertices,
                 const Eigen::MatrixXd& directions) {
  std::vector<int> columns;
  const LaplacianCoordinates rows = energy.coordinates().restricted(vertices, columns);
  Eigen::MatrixXd images;  // W Z at the columns
  W.select_rows(columns).multiply(directions, images);
  const int q = static_cast<int>(directions.cols() / 3), per_pose = 1 + q;
  const Eigen::Index count = static_cast<Eigen::Index>(vertices.size());
  FitData fit{Eigen::MatrixXd(per_pose * static_cast<Eigen::Index>(poses.size()), count),
              Eigen::VectorXd(per_pose * static_cast<Eigen::Index>(poses.size()))};
  EnergyJacobian J(energy);
  LaplacianRows M(&rows.laplacian_blocks());
  for (size_t t = 0; t < poses.size(); ++t) {
    Eigen::MatrixXd image;
    W.multiply(poses[t] - U0, image);
    const Vertices X = energy.rest_positions() + image;
    // The sums over every vertex: the energy, and its gradient in the unknowns (W^T M^T r) along the directions.
    const EnergyEvaluation e = energy.evaluate(X);
    energy.update_jacobian(X, J);
    Eigen::MatrixXd gradient;
    W.multiply_transpose(J.laplacian_rows_transpose(e.laplacian_residual), gradient);
    // Each vertex's own terms: e_i and r_i . (M Y_l)_i.
    Vertices Xc(static_cast<Eigen::Index>(columns.size()), 3);
    for (size_t k = 0; k < columns.size(); ++k) Xc.row(static_cast<Eigen::Index>(k)) = X.row(columns[k]);
    rows.jacobian_factors(Xc, M.delta_hat_jacobian());
    const Eigen::MatrixXd MY = M.multiply(images);
    const Eigen::Index row0 = per_pose * static_cast<Eigen::Index>(t);
    fit.b[row0] = e.laplacian_energy;
    for (Eigen::Index i = 0; i < count; ++i) fit.A(row0, i) = 0.5 * e.laplacian_residual.row(vertices[i]).squaredNorm();
    for (int l = 0; l < q; ++l) {
      fit.b[row0 + 1 + l] = block_dot(gradient, directions.middleCols(3 * l, 3));
      for (Eigen::Index i = 0; i < count; ++i)
        fit.A(row0 + 1 + l, i) = e.laplacian_residual.row(vertices[i]).dot(MY.row(i).segment(3 * l, 3));
    }
    const double energy_scale = std::abs(fit.b[row0]), slope_scale = fit.b.segment(row0 + 1, q).norm();
    if (energy_scale > 0.0) {
      fit.A.row(row0) /= energy_scale;
      fit.b[row0] /= energy_scale;
    }
    if (slope_scale > 0.0) {
      fit.A.middleRows(row0 + 1, q) /= slope_scale;
      fit.b.segment(row0 + 1, q) /= slope_scale;
    }
  }
  return fit;
}

double relative_error(const FitData& data, const Eigen::VectorXd& w) {
  return data.b.norm() > 0.0 ? (data.A * w - data.b).norm() / data.b.norm() : 0.0;
}

// Fits w = prior x v, v >= 0, minimising |A w - b|^2 + mu |v - 1|^2.
Eigen::VectorXd fit_weights(const FitData& data, const Eigen::VectorXd& prior, double pull) {
  const Eigen::MatrixXd scaled = data.A * prior.asDiagonal();
  const Eigen::Index k = scaled.cols();
  const double mu = pull * scaled.squaredNorm() / static_cast<double>(k);
  Eigen::MatrixXd A(scaled.rows() + k, k);
  A << scaled, std::sqrt(mu) * Eigen::MatrixXd::Identity(k, k);
  Eigen::VectorXd b(A.rows());
  b << data.b, std::sqrt(mu) * Eigen::VectorXd::Ones(k);
  return prior.cwiseProduct(nonnegative_least_squares(A, b));
}

Eigen::MatrixXd random_directions(int m, int count, PortableRandom& random) {
  Eigen::MatrixXd Z(m, 3 * count);
  for (Eigen::Index k = 0; k < Z.size(); ++k) Z.data()[k] = random.gaussian();
  for (int l = 0; l < count; ++l) Z.middleCols(3 * l, 3).normalize();
  return Z;
}

// Keeps the samples with a positive weight.
void drop_zero_weights(Cubature& c) {
  std::vector<int> samples;
  std::vector<double> weights, quadrature;
  for (size_t k = 0; k < c.samples.size(); ++k)
    if (c.weights[static_cast<Eigen::Index>(k)] > 0.0) {
      samples.push_back(c.samples[k]);
      weights.push_back(c.weights[static_cast<Eigen::Index>(k)]);
      quadrature.push_back(c.quadrature[static_cast<Eigen::Index>(k)]);
    }
  c.samples = std::move(samples);
  c.weights = Eigen::Map<Eigen::VectorXd>(weights.data(), static_cast<Eigen::Index>(weights.size()));
  c.quadrature = Eigen::Map<Eigen::VectorXd>(quadrature.data(), static_cast<Eigen::Index>(quadrature.size()));
}

}  // namespace

Cubature fit_cubature(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                      const CubatureOptions& options) {
  const Timer timer;
  Cubature out;
  const int n = energy.vertex_count();
  if (n <= options.max_samples) {  // every vertex: the sum itself
    out.samples.resize(n);
    std::iota(out.samples.begin(), out.samples.end(), 0);
    out.weights = Eigen::VectorXd::Ones(n);
    out.quadrature = out.weights;
    out.candidates = n;
    out.ms = timer.ms();
    return out;
  }
  PortableRandom random(options.seed);
  const Eigen::MatrixXd directions = random_directions(W.cols(), options.directions, random);
  const std::vector<Eigen::MatrixXd> poses =
      training_poses(energy.rest_positions(), W, U0, options.training_poses + options.test_poses, options.seed);
  const std::vector<Eigen::MatrixXd> training(poses.begin(), poses.begin() + options.training_poses),
      test(poses.begin() + options.training_poses, poses.end());
  if (options.selection == CubatureOptions::Selection::Greedy) {
    const std::vector<int> candidates = random_vertices(n, options.greedy_candidates, random);
    const FitData data = assemble(energy, W, U0, training, candidates, directions);
    const NnlsFit fit = greedy_nnls(data.A, data.b, options.max_samples, 1e-3);
    for (int k : fit.columns) out.samples.push_back(candidates[k]);
    out.weights = fit.weights;
    out.quadrature = fit.weights;  // no cells: the fitted weights are the rule
    out.training_error = fit.relative_error;
    out.candidates = static_cast<int>(candidates.size());
  } else {
    std::vector<int> exact = options.exact_vertices;
    if (static_cast<int>(exact.size()) > options.max_samples / 2)
      exact.resize(static_cast<size_t>(options.max_samples / 2));
    spread_samples(energy, options.max_samples - static_cast<int>(exact.size()), exact, random, out.samples,
                   out.weights);
    out.exact = static_cast<int>(exact.size());
    out.quadrature = out.weights;
    out.candidates = std::min(n, kSpreadPool);
    if (!training.empty()) {
      const FitData data = assemble(energy, W, U0, training, out.samples, directions);
      out.weights = fit_weights(data, out.weights, options.prior_pull);
      out.training_error = relative_error(data, out.weights);
    }
  }
  drop_zero_weights(out);
  if (!test.empty()) {
    const FitData data = assemble(energy, W, U0, test, out.samples, directions);
    out.test_error = relative_error(data, out.weights);
  }
  out.ms = timer.ms();
  return out;
}

}  // namespace sd
