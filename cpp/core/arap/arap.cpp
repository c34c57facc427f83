#include "core/arap/arap.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/arap/internal/anderson_acceleration.h"
#include "core/mesh/cotan_laplacian.h"
#include "core/error.h"
#include "core/mesh/volume.h"
#include "core/parallel/parallel_for.h"
#include "core/parallel/solve_columns.h"
#include "core/timer.h"

namespace sd {
namespace {

constexpr double kWeightFloorRel = 1e-3;  // negative cotangent weights are raised to this times mean |w|
constexpr int kVertexBlock = 1024;        // vertices per task of the local step and the right-hand sides

}  // namespace

namespace {

// Reference path: R = V U^T from the SVD S = U Sigma V^T. Singular values come sorted in decreasing
// order, so the last column belongs to the smallest one: flipping it when det < 0 costs the least of
// trace(R S) among proper rotations.
Eigen::Matrix3d rotation_by_svd(const Eigen::Matrix3d& S) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d V = svd.matrixV();
  if ((V * U.transpose()).determinant() < 0.0) U.col(2) = -U.col(2);
  return V * U.transpose();
}

// Fast path (2-3x cheaper than JacobiSVD, which dominated the iteration): the right singular vectors
// from the closed-form eigen-decomposition of S^T S, the left ones as S v / |S v|, the third of each as
// the cross product of the first two (so R is proper and the smallest direction is flipped exactly
// when det S < 0), then one Newton step on trace(R S) over rotations to recover full precision
// (the closed form loses a few digits). Returns false when S is too close to a case where the optimum
// is ill-determined (rank <= 1, or sigma_2 ~ -sigma_3 after the flip); the SVD path handles those.
bool rotation_by_eigen(const Eigen::Matrix3d& S, Eigen::Matrix3d& R) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(S.transpose() * S);  // eigenvalues ascending
  const Eigen::Vector3d v1 = eig.eigenvectors().col(2);
  const Eigen::Vector3d v2 = (eig.eigenvectors().col(1) - eig.eigenvectors().col(1).dot(v1) * v1).normalized();
  Eigen::Vector3d u1 = S * v1, u2 = S * v2;
  const double s1 = u1.norm();
  if (!(s1 > 0.0)) return false;
  u1 /= s1;
  u2 -= u2.dot(u1) * u1;
  const double s2 = u2.norm();
  if (!(s2 > 1e-4 * s1)) return false;
  u2 /= s2;
  R = v1 * u1.transpose() + v2 * u2.transpose() + v1.cross(v2) * u1.cross(u2).transpose();
  // Newton on f(w) = trace(exp([w]x) R S): gradient b = axial part of M = R S, Hessian trace(M) I - sym(M),
  // positive definite at a well-determined optimum.
  const Eigen::Matrix3d M = R * S;
  const Eigen::Vector3d b(M(1, 2) - M(2, 1), M(2, 0) - M(0, 2), M(0, 1) - M(1, 0));
  const Eigen::Matrix3d H = M.trace() * Eigen::Matrix3d::Identity() - 0.5 * (M + M.transpose());
  const Eigen::LLT<Eigen::Matrix3d> llt(H);
  if (llt.info() != Eigen::Success || !(H.determinant() > 1e-12 * std::pow(H.trace(), 3))) return false;
  const Eigen::Vector3d w = llt.solve(b);
  const double angle = w.norm();
  if (!(angle < 1e-3)) return false;  // the closed form was far off: not a case to trust it
  if (angle > 0.0) {
    const Eigen::Matrix3d refined = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix() * R;
    if ((refined * S).trace() >= M.trace()) R = refined;
  }
  return R.allFinite();
}

}  // namespace

Eigen::Matrix3d arap_best_rotation(const Eigen::Matrix3d& S) {
  // A zero or non-finite covariance carries no orientation: the identity is the safe answer.
  // (allFinite first: maxCoeff skips NaN.)
  if (!S.allFinite()) return Eigen::Matrix3d::Identity();
  const double size = S.cwiseAbs().maxCoeff();
  if (!(size > 0.0)) return Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d unit = S / size;
  Eigen::Matrix3d R;
  if (rotation_by_eigen(unit, R)) return R;
  R = rotation_by_svd(unit);
  return R.allFinite() ? R : Eigen::Matrix3d::Identity();
}

struct ArapSolver::Impl {
  int n = 0;
  Faces F;
  Vertices X0;
  double rest_volume = 0;
  VolumeReference volume_reference;  // the rest mesh's, fixed: the volumes of the statistics are summed about it
  // Half-edges in CSR order: neighbours of i are nbr[off[i] .. off[i+1]) with weight w and rest edge
  // e0 = x0_i - x0_j.
  std::vector<int> off, nbr;
  std::vector<double> w;
  std::vector<Eigen::Vector3d> e0;
  int clamped = 0;
  std::vector<int> component;  // connected component of each vertex
  int component_count = 0;

  // Per handle set.
  std::vector<int> handles;
  std::vector<int> free_index;  // vertex -> row of the free system, -1 for handles and passive vertices
  std::vector<int> free_vertices;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  bool factorized = false;
  double factor_ms = 0;
  int iteration = 0;

  // Rotations of the last local step and the positions they were computed from (the warm start: the
  // local step that ends one iteration is the one that begins the next).
  std::vector<Eigen::Matrix3d> R;
  Vertices R_source;
  double R_energy = 0;  // the energy at R_source with R

  AndersonAcceleration anderson{5};
  Vertices last_targets;  // the map G changes with the targets: the history is reset then
  int rejected = 0;

  // Best rotation of every vertex for positions X; returns the energy with those rotations (fused so the
  // one-ring is read while it is in cache).
  double local_step(const Vertices& X, std::vector<Eigen::Matrix3d>& out) const {
    out.resize(n);
    // Vertices are independent; the energy adds per-block sums in block order (cpp/core/parallel), so
    // rotations and energy are the same with any number of threads.
    return parallel::parallel_sum(0, n, kVertexBlock, [&](int lo, int hi) {
      double energy = 0;
      for (int i = lo; i < hi; ++i) {
        Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
        const Eigen::Vector3d xi = X.row(i).transpose();
        for (int h = off[i]; h < off[i + 1]; ++h)
          S.noalias() += (w[h] * e0[h]) * (xi - X.row(nbr[h]).transpose()).transpose();
        out[i] = arap_best_rotation(S);
        for (int h = off[i]; h < off[i + 1]; ++h)
          energy += w[h] * ((xi - X.row(nbr[h]).transpose()) - out[i] * e0[h]).squaredNorm();
      }
      return energy;
    });
  }

  // Throws sd::Error unless X has a finite row per vertex and `targets` (when given) one per handle vertex.
  void check(const Vertices& X, const Vertices* targets) const {
    if (X.rows() != n)
      throw Error("ARAP: X has " + std::to_string(X.rows()) + " rows, the mesh has " + std::to_string(n) + " vertices");
    if (targets && targets->rows() != static_cast<Eigen::Index>(handles.size()))
      throw Error("ARAP: " + std::to_string(targets->rows()) + " targets given for " + std::to_string(handles.size()) +
                  " handle vertices");
    if (!X.allFinite() || (targets && !targets->allFinite())) throw Error("ARAP: positions or targets are not finite");
  }

  // The energy of positions X with fixed rotations `rotations` (in block order, like local_step).
  double energy_with(const Vertices& X, const std::vector<Eigen::Matrix3d>& rotations) const {
    return parallel::parallel_sum(0, n, kVertexBlock, [&](int lo, int hi) {
      double energy = 0;
      for (int i = lo; i < hi; ++i) {
        const Eigen::Vector3d xi = X.row(i).transpose();
        for (int h = off[i]; h < off[i + 1]; ++h)
          energy += w[h] * ((xi - X.row(nbr[h]).transpose()) - rotations[i] * e0[h]).squaredNorm();
      }
      return energy;
    });
  }

  // Global step: sum_j w_ij (x_i - x_j) = sum_j w_ij / 2 (R_i + R_j)(x0_i - x0_j) for the free vertices, with
  // handle and passive neighbours (whose rows X already holds) moved to the right-hand side.
  void global_solve(Vertices& X) const {
    if (!factorized) return;
    const int nf = static_cast<int>(free_vertices.size());
    Eigen::Matrix<double, Eigen::Dynamic, 3> rhs(nf, 3);
    parallel::parallel_for(0, nf, kVertexBlock, [&](int lo, int hi) {
      for (int r = lo; r < hi; ++r) {
        const int i = free_vertices[r];
        Eigen::Vector3d b = Eigen::Vector3d::Zero();
        for (int h = off[i]; h < off[i + 1]; ++h) {
          const int j = nbr[h];
          b += (0.5 * w[h]) * ((R[i] + R[j]) * e0[h]);
          if (free_index[j] < 0) b += w[h] * X.row(j).transpose();
        }
        rhs.row(r) = b.transpose();
      }
    });
    // x, y and z: three independent solves with the one factorization.
    const Eigen::Matrix<double, Eigen::Dynamic, 3> solution = parallel::solve_columns(solver, rhs);
    if (!solution.allFinite()) throw Error(ErrorCode::NumericalFailure, "ARAP: numerical failure in the global solve");
    for (int r = 0; r < nf; ++r) X.row(free_vertices[r]) = solution.row(r);
  }

  // The mean and largest rotation angle of the current rotations R, into `half`.
  void rotation_angles(ArapHalfStep& half) const {
    double sum = 0, largest = 0;
    for (const Eigen::Matrix3d& r : R) {
      const double angle = std::acos(std::clamp((r.trace() - 1.0) / 2.0, -1.0, 1.0));
      sum += angle;
      largest = std::max(largest, angle);
    }
    half.mean_rotation = R.empty() ? 0.0 : sum / static_cast<double>(R.size());
    half.max_rotation = largest;
  }

  // X holds G(x) for x = previous. Replaces it by the Anderson extrapolation when that has a lower ARAP
  // energy than previous (Peng et al.'s safeguard), else keeps G(x) and restarts the history. Leaves the
  // best rotations for the returned X in R and returns its energy.
  double accelerate(const Vertices& previous, Vertices& X, double previous_energy) {
    const Eigen::Map<const Eigen::VectorXd> x(previous.data(), previous.size());
    const Eigen::Map<const Eigen::VectorXd> g(X.data(), X.size());
    Vertices candidate(X.rows(), 3);
    Eigen::Map<Eigen::VectorXd>(candidate.data(), candidate.size()) = anderson.next(x, g);
    for (size_t k = 0; k < handles.size(); ++k) candidate.row(handles[k]) = X.row(handles[k]);  // exact targets
    if (candidate.allFinite() && candidate != X) {
      std::vector<Eigen::Matrix3d> rotations;
      const double candidate_energy = local_step(candidate, rotations);
      if (candidate_energy < previous_energy) {
        X = std::move(candidate);
        R = std::move(rotations);
        return candidate_energy;
      }
      ++rejected;
      anderson.reset();
    }
    return local_step(X, R);
  }
};

ArapSolver::ArapSolver(const Vertices& X0, const Faces& F) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.n = static_cast<int>(X0.rows());
  if (m.n == 0 || F.rows() == 0) throw Error(ErrorCode::InvalidMesh, "ARAP: the mesh is empty");
  m.F = F;
  m.X0 = X0;
  const Eigen::SparseMatrix<double> L = cotan_laplacian(X0, F);  // validates indices and triangles
  m.volume_reference = volume_reference(X0, F);
  m.rest_volume = signed_volume(X0, F, m.volume_reference);

  double mean_abs = 0;
  int count = 0;
  for (int k = 0; k < L.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it)
      if (it.row() != it.col()) mean_abs += std::abs(it.value()), ++count;
  mean_abs = count ? mean_abs / count : 1.0;
  const double floor = kWeightFloorRel * mean_abs;

  // L is symmetric, so column k lists the neighbours of vertex k.
  m.off.assign(1, 0);
  for (int k = 0; k < L.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it) {
      const int j = static_cast<int>(it.row());
      if (j == k) continue;
      double weight = it.value();
      if (!(weight >= floor)) weight = floor, ++m.clamped;
      m.nbr.push_back(j);
      m.w.push_back(weight);
      m.e0.push_back((X0.row(k) - X0.row(j)).transpose());
    }
    m.off.push_back(static_cast<int>(m.nbr.size()));
  }
  m.clamped /= 2;  // each edge was seen from both ends

  // Connected components (iterative flood fill over the half-edges).
  m.component.assign(m.n, -1);
  std::vector<int> stack;
  int components = 0;
  for (int s = 0; s < m.n; ++s) {
    if (m.component[s] >= 0) continue;
    m.component[s] = components;
    stack.push_back(s);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int h = m.off[v]; h < m.off[v + 1]; ++h)
        if (m.component[m.nbr[h]] < 0) m.component[m.nbr[h]] = components, stack.push_back(m.nbr[h]);
    }
    ++components;
  }
  m.component_count = components;
  m.R.assign(m.n, Eigen::Matrix3d::Identity());
  set_handles({});
}

ArapSolver::~ArapSolver() = default;

void ArapSolver::set_handles(const std::vector<int>& handle_vertices) {
  Impl& m = *impl_;
  const Timer timer;
  for (size_t k = 0; k < handle_vertices.size(); ++k) {
    const int h = handle_vertices[k];
    if (h < 0 || h >= m.n)
      throw Error("ARAP: handle vertex " + std::to_string(h) + " is outside [0, " + std::to_string(m.n) + ")");
    if (k > 0 && h <= handle_vertices[k - 1])
      throw Error("ARAP: handle vertices must be sorted and unique (vertex " + std::to_string(h) + " at position " +
                  std::to_string(k) + ")");
  }
  m.handles = handle_vertices;
  m.iteration = 0;

  // Free = not a handle and in a component that has a handle; everything else is held where it is.
  std::vector<char> anchored(m.n, 0), is_handle(m.n, 0);
  std::vector<char> component_has_handle(m.component_count, 0);
  for (int h : m.handles) is_handle[h] = 1, component_has_handle[m.component[h]] = 1;
  m.free_index.assign(m.n, -1);
  m.free_vertices.clear();
  for (int v = 0; v < m.n; ++v)
    if (!is_handle[v] && component_has_handle[m.component[v]]) {
      m.free_index[v] = static_cast<int>(m.free_vertices.size());
      m.free_vertices.push_back(v);
    }

  // Free block of the weighted graph Laplacian: diagonal sum_j w_ij, off-diagonal -w_ij.
  const int nf = static_cast<int>(m.free_vertices.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (int r = 0; r < nf; ++r) {
    const int i = m.free_vertices[r];
    double diagonal = 0;
    for (int h = m.off[i]; h < m.off[i + 1]; ++h) {
      diagonal += m.w[h];
      const int c = m.free_index[m.nbr[h]];
      if (c >= 0) entries.emplace_back(r, c, -m.w[h]);
    }
    entries.emplace_back(r, r, diagonal);
  }
  m.factorized = false;
  if (nf > 0) {
    Eigen::SparseMatrix<double> A(nf, nf);
    A.setFromTriplets(entries.begin(), entries.end());
    m.solver.compute(A);
    if (m.solver.info() != Eigen::Success)
      throw Error(ErrorCode::NumericalFailure,
                  "ARAP: the global system could not be factorized (" + std::to_string(nf) + " free vertices)");
    m.factorized = true;
  }
  m.R_source.resize(0, 3);  // positions may be reset by the caller; recompute rotations next time
  m.factor_ms = timer.ms();
}

IterationStats ArapSolver::iterate(Vertices& X, const Vertices& targets) {
  Impl& m = *impl_;
  const Timer timer;
  m.check(X, &targets);

  const Vertices previous = X;
  for (size_t k = 0; k < m.handles.size(); ++k) X.row(m.handles[k]) = targets.row(static_cast<int>(k));

  // Local step from the current positions (reused when the last iteration ended at exactly this X).
  const bool continuing = m.R_source.rows() == m.n && m.R_source == previous;
  const double previous_energy = continuing ? m.R_energy : m.local_step(previous, m.R);
  if (!continuing || m.last_targets.rows() != targets.rows() || m.last_targets != targets) m.anderson.reset();
  m.last_targets = targets;

  m.global_solve(X);

  // Best rotations for the new positions: they give the energy now and start the next iteration.
  double energy = 0;
  const int rejected_before = m.rejected;
  if (m.anderson.depth() > 0) {
    energy = m.accelerate(previous, X, previous_energy);
  } else {
    energy = m.local_step(X, m.R);
  }
  m.R_source = X;
  m.R_energy = energy;

  IterationStats stats;
  stats.iteration = ++m.iteration;
  stats.energy = stats.merit = stats.laplacian_energy = energy;
  stats.fallbacks = m.rejected - rejected_before;  // the extrapolation was rejected: a plain step
  stats.volume = signed_volume(X, m.F, m.volume_reference);
  stats.volume_rel_error = m.rest_volume != 0 ? (stats.volume - m.rest_volume) / m.rest_volume : 0.0;
  stats.step = (X - previous).rowwise().norm().maxCoeff();
  stats.ms = timer.ms();
  return stats;
}

ArapHalfStep ArapSolver::local_half_step(const Vertices& X) {
  Impl& m = *impl_;
  m.check(X, nullptr);
  ArapHalfStep half;
  half.local = true;
  half.energy_before = m.energy_with(X, m.R);
  half.energy_after = m.local_step(X, m.R);
  m.R_source = X;  // an iterate() from X goes on with these rotations
  m.R_energy = half.energy_after;
  m.anderson.reset();
  m.rotation_angles(half);
  return half;
}

ArapHalfStep ArapSolver::global_half_step(Vertices& X, const Vertices& targets) {
  Impl& m = *impl_;
  m.check(X, &targets);
  ArapHalfStep half;
  half.local = false;
  const Vertices previous = X;
  for (size_t k = 0; k < m.handles.size(); ++k) X.row(m.handles[k]) = targets.row(static_cast<int>(k));
  half.energy_before = m.energy_with(X, m.R);  // the handles at their targets: what the solve starts from
  m.global_solve(X);
  half.energy_after = m.energy_with(X, m.R);
  half.step = (X - previous).rowwise().norm().maxCoeff();
  m.R_source.resize(0, 3);  // the rotations are no longer the best for X: the next iteration starts afresh
  m.anderson.reset();
  m.rotation_angles(half);
  return half;
}

void ArapSolver::set_acceleration(int depth) { impl_->anderson.set_depth(depth); }
int ArapSolver::rejected_accelerations() const { return impl_->rejected; }

double ArapSolver::energy(const Vertices& X) const {
  if (X.rows() != impl_->n)
    throw Error("ARAP: X has " + std::to_string(X.rows()) + " rows, the mesh has " + std::to_string(impl_->n) +
                " vertices");
  std::vector<Eigen::Matrix3d> rot;
  return impl_->local_step(X, rot);
}

const std::vector<Eigen::Matrix3d>& ArapSolver::rotations() const { return impl_->R; }
int ArapSolver::clamped_weight_count() const { return impl_->clamped; }
double ArapSolver::factorization_ms() const { return impl_->factor_ms; }

}  // namespace sd
