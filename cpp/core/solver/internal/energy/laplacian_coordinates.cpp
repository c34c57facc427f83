#include "core/solver/internal/energy/laplacian_coordinates.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "core/error.h"
#include "core/parallel/parallel_for.h"

namespace sd {
namespace {

// Thresholds of the rest-pose fit, relative so they do not depend on the model's units.
constexpr double kSmallDeltaRel = 1e-9;  // |delta_i| below this times the local scale: "no direction"
constexpr double kResidualRel = 1e-9;    // min-norm solve must reproduce delta_i to this, relatively
constexpr double kRankRel = 1e-12;       // singular values below this times the largest count as zero
constexpr double kNormFloorRel = 1e-12;  // |d_i(X)| is clamped below at this times its rest magnitude

// Every per-vertex loop here writes only its own vertex's entries, so any split over threads gives the same
// bits (cpp/core/parallel). Vertices per task: one-rings of ~6 edges, a few microseconds per block.
constexpr int kVertexBlock = 512;

// c = (x_a - x_i) x (x_b - x_i): twice the area times the outward normal of triangle (i, a, b).
Eigen::Vector3d corner_cross(const Vertices& X, int i, int a, int b) {
  const Eigen::Vector3d xi = X.row(i).transpose();
  return (X.row(a).transpose() - xi).cross(X.row(b).transpose() - xi);
}

// The links a -> b of vertex i: one per triangle (i, a, b) in outward (counter-clockwise) order. Walking a -> b
// around i visits the one-ring in the order of the outward faces.
std::vector<std::vector<std::pair<int, int>>> ring_links(const Faces& F, int n) {
  std::vector<std::vector<std::pair<int, int>>> next(n);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int i = F(f, k), a = F(f, (k + 1) % 3), b = F(f, (k + 2) % 3);
      if (i < 0 || i >= n || a < 0 || a >= n || b < 0 || b >= n)
        throw Error(ErrorCode::InvalidMesh, "Laplacian coordinates: triangle " + std::to_string(f) +
                                                " has a vertex index outside [0, " + std::to_string(n) + ")");
      next[i].push_back({a, b});
    }
  return next;
}

// Orders the links of vertex i (sorted by a) into its one-ring. A closed fan j_1 .. j_k is stored rotated so
// that element t pairs with the triangle (i, j_{t-1}, j_t), element 0 closing the loop from j_k; an open fan
// (the one neighbour that starts a link but ends none is its first) as j_0 .. j_k, element 0 then pairing with
// the missing triangle. Returns whether the fan is open; throws naming the vertex when it is not one fan.
bool order_fan(int i, const std::vector<std::pair<int, int>>& links, std::vector<int>& ring) {
  const int k = static_cast<int>(links.size());
  const auto fail = [&](const std::string& why) {
    return Error(ErrorCode::InvalidMesh, "Laplacian coordinates: the one-ring of vertex " + std::to_string(i) +
                                             " cannot be ordered (" + why +
                                             "); the mesh must be manifold and consistently oriented");
  };
  if (k == 0) throw fail("no triangle uses it");
  for (int e = 0; e + 1 < k; ++e)
    if (links[e].first == links[e + 1].first)
      throw fail("two triangles start at neighbour " + std::to_string(links[e].first));
  const auto successor = [&](int a) {
    const auto it = std::lower_bound(links.begin(), links.end(), std::make_pair(a, -1));
    return (it != links.end() && it->first == a) ? it->second : -1;
  };
  // An open fan starts at the neighbour no link ends at.
  std::vector<int> ends;
  for (const auto& link : links) ends.push_back(link.second);
  std::sort(ends.begin(), ends.end());
  int start = links[0].first;
  bool open = false;
  for (const auto& link : links)
    if (!std::binary_search(ends.begin(), ends.end(), link.first)) {
      if (open) throw fail("its triangles form more than one fan");
      start = link.first;
      open = true;
    }
  if (!open && k < 3) throw fail(std::to_string(k) + " incident triangles");
  std::vector<int> walk{start};
  for (int current = start, step = 0; step < k; ++step) {
    current = successor(current);
    if (current < 0 || current == start) break;
    walk.push_back(current);
  }
  if (static_cast<int>(walk.size()) != (open ? k + 1 : k) || (!open && successor(walk.back()) != start))
    throw fail("its triangles form more than one fan");
  if (open) {
    ring.insert(ring.end(), walk.begin(), walk.end());
  } else {
    ring.insert(ring.end(), walk.begin() + 1, walk.end());
    ring.push_back(start);
  }
  return open;
}

}  // namespace

LaplacianCoordinates::LaplacianCoordinates(const Vertices& X0, const Faces& F, const Eigen::SparseMatrix<double>& L) {
  const int n = static_cast<int>(X0.rows());
  if (L.rows() != n || L.cols() != n)
    throw Error("Laplacian coordinates: L is " + std::to_string(L.rows()) + " x " + std::to_string(L.cols()) +
                " but the mesh has " + std::to_string(n) + " vertices");
  order_one_rings(F, n);
  build_block_pattern(n);
  copy_laplacian_blocks(L);
  fit_rest_pose(X0, L * X0, L);
}

void LaplacianCoordinates::order_one_rings(const Faces& F, int n) {
  std::vector<std::vector<std::pair<int, int>>> links = ring_links(F, n);
  ring_offsets_.assign(1, 0);
  boundary_.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    std::sort(links[i].begin(), links[i].end());
    boundary_[i] = order_fan(i, links[i], ring_);
    ring_offsets_.push_back(static_cast<int>(ring_.size()));
  }
}

void LaplacianCoordinates::build_block_pattern(int n) {
  auto pattern = std::make_shared<BlockPattern>();
  pattern->row_start.resize(n + 1);
  for (int i = 0; i < n; ++i) {
    pattern->row_start[i] = ring_offsets_[i] + i;
    pattern->column.push_back(i);
    pattern->column.insert(pattern->column.end(), ring_.begin() + ring_offsets_[i],
                           ring_.begin() + ring_offsets_[i + 1]);
  }
  pattern->row_start[n] = static_cast<int>(pattern->column.size());
  pattern->index_columns();
  block_pattern_ = std::move(pattern);
}

void LaplacianCoordinates::copy_laplacian_blocks(const Eigen::SparseMatrix<double>& L) {
  laplacian_blocks_.resize(block_pattern_->column.size());
  parallel::parallel_for(0, vertex_count(), kVertexBlock, [&](int lo, int hi) {
    for (int i = lo; i < hi; ++i)
      for (int k = block_pattern_->row_start[i]; k < block_pattern_->row_start[i + 1]; ++k)
        laplacian_blocks_[k] = L.coeff(i, block_pattern_->column[k]);
  });
}

Eigen::SparseMatrix<double> LaplacianCoordinates::laplacian() const {
  const BlockPattern& p = *block_pattern_;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(laplacian_blocks_.size());
  for (int i = 0; i < p.vertex_count(); ++i)
    for (int k = p.row_start[i]; k < p.row_start[i + 1]; ++k)
      entries.emplace_back(i, p.column[k], laplacian_blocks_[k]);
  Eigen::SparseMatrix<double> L(p.vertex_count(), p.vertex_count());
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

// Rest fit of mu and gamma (and, at boundary vertices, of their Laplacian rows) so that delta_hat(X0) = L' X0.
void LaplacianCoordinates::fit_rest_pose(const Vertices& X0, const Vertices& delta,
                                         const Eigen::SparseMatrix<double>& L) {
  const int n = vertex_count();
  mu_.assign(ring_.size(), 1.0);
  gamma_.assign(n, 0.0);
  d_floor_.assign(n, 0.0);
  std::vector<char> fell_back(n, 0);
  parallel::parallel_for(0, n, kVertexBlock / 4, [&](int lo, int hi) {
    for (int i = lo; i < hi; ++i) {
      const Eigen::Vector3d di = delta.row(i).transpose();
      const bool fitted = boundary_[i] ? fit_boundary_vertex(X0, di, i) : fit_closed_vertex(X0, di, L, i);
      fell_back[i] = !fitted;
      set_norm_floor(X0, i);
    }
  });
  fallback_count_ = static_cast<int>(std::count(fell_back.begin(), fell_back.end(), 1));
}

bool LaplacianCoordinates::fit_closed_vertex(const Vertices& X0, const Eigen::Vector3d& di,
                                             const Eigen::SparseMatrix<double>& L, int i) {
  const int begin = ring_offsets_[i], k = ring_offsets_[i + 1] - begin;
  Eigen::Matrix3Xd C(3, k);
  double scale = 0.0;  // size of the terms that sum to delta_i
  for (int t = 0; t < k; ++t) {
    const int prev = ring_[begin + (t + k - 1) % k], cur = ring_[begin + t];
    C.col(t) = corner_cross(X0, i, prev, cur);
    scale += std::abs(L.coeff(i, cur)) * (X0.row(cur) - X0.row(i)).norm();
  }
  bool use_fit = di.norm() > kSmallDeltaRel * scale;
  Eigen::VectorXd mu;
  if (use_fit) {
    // Minimum-norm least-squares solution (pseudo-inverse), singular values below kRankRel times the
    // largest treated as zero. (The full-pivoting preconditioner also avoids a GCC false-positive
    // -Wmaybe-uninitialized inside Eigen's column-pivoting one.)
    Eigen::JacobiSVD<Eigen::MatrixXd, Eigen::FullPivHouseholderQRPreconditioner> svd(
        C, Eigen::ComputeFullU | Eigen::ComputeFullV);
    svd.setThreshold(kRankRel);
    mu = svd.solve(di);
    use_fit = mu.allFinite() && (C * mu - di).norm() <= kResidualRel * di.norm();
  }
  if (use_fit) {
    gamma_[i] = di.norm();
  } else {
    // Area-weighted normal direction with the part of delta_i along it (docs/method.md section 4).
    mu = Eigen::VectorXd::Ones(k);
    const Eigen::Vector3d d = C * mu;
    gamma_[i] = d.norm() > 0 ? di.dot(d) / d.norm() : 0.0;
  }
  for (int t = 0; t < k; ++t) mu_[begin + t] = mu(t);
  return use_fit;
}

bool LaplacianCoordinates::fit_boundary_vertex(const Vertices& X0, const Eigen::Vector3d& di, int i) {
  const int begin = ring_offsets_[i], k = ring_offsets_[i + 1] - begin;  // k neighbours, k - 1 triangles
  // d_i: the area-weighted normal of the existing triangles (slot 0, the missing one, weighs nothing).
  mu_[begin] = 0.0;
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  Eigen::Matrix3Xd E(3, k);  // ring edges x0_j - x0_i
  for (int t = 0; t < k; ++t) {
    E.col(t) = (X0.row(ring_[begin + t]) - X0.row(i)).transpose();
    if (t > 0) d += corner_cross(X0, i, ring_[begin + t - 1], ring_[begin + t]);
  }
  gamma_[i] = d.norm() > 0 ? di.dot(d) / d.norm() : 0.0;
  const Eigen::Vector3d tangential = d.norm() > 0 ? Eigen::Vector3d(di - gamma_[i] * d / d.norm()) : di;
  // The tangential rest as a fixed combination of the ring's edges, moved into row i of the Laplacian.
  Eigen::JacobiSVD<Eigen::MatrixXd, Eigen::FullPivHouseholderQRPreconditioner> svd(
      E, Eigen::ComputeFullU | Eigen::ComputeFullV);
  svd.setThreshold(kRankRel);
  const Eigen::VectorXd nu = svd.solve(tangential);
  if (!nu.allFinite() || (E * nu - tangential).norm() > kResidualRel * std::max(di.norm(), tangential.norm()))
    return false;  // a degenerate fan: its rows stay those of L, and delta_hat keeps the normal part only
  double* row = &laplacian_blocks_[block_pattern_->row_start[i]];  // slot 0: L_ii, slot 1 + t: L_{i, ring[t]}
  for (int t = 0; t < k; ++t) {
    row[1 + t] -= nu(t);
    row[0] += nu(t);
  }
  return true;
}

void LaplacianCoordinates::set_norm_floor(const Vertices& X0, int i) {
  const int begin = ring_offsets_[i], k = ring_offsets_[i + 1] - begin;
  double magnitude = 0.0;
  for (int t = 0; t < k; ++t)
    magnitude +=
        std::abs(mu_[begin + t]) * corner_cross(X0, i, ring_[begin + (t + k - 1) % k], ring_[begin + t]).norm();
  d_floor_[i] = kNormFloorRel * magnitude;
}

void LaplacianCoordinates::check_rows(const Vertices& X) const {
  if (X.rows() != column_count())
    throw Error("Laplacian coordinates: X has " + std::to_string(X.rows()) + " rows, expected " +
                std::to_string(column_count()));
}

LaplacianCoordinates LaplacianCoordinates::restricted(const std::vector<int>& rows, std::vector<int>& columns) const {
  // The columns: the rows' own vertices and one-rings, increasing (so gathering their positions reads memory in
  // order), numbered locally through a map over all columns.
  std::vector<char> used(static_cast<size_t>(column_count()), 0);
  for (int i : rows) {
    if (i < 0 || i >= vertex_count())
      throw Error("Laplacian coordinates: row " + std::to_string(i) + " outside [0, " + std::to_string(vertex_count()) +
                  ")");
    used[self(i)] = 1;
    for (int k = ring_offsets_[i]; k < ring_offsets_[i + 1]; ++k) used[ring_[k]] = 1;
  }
  columns.clear();
  std::vector<int> local(used.size(), -1);
  for (size_t j = 0; j < used.size(); ++j)
    if (used[j]) {
      local[j] = static_cast<int>(columns.size());
      columns.push_back(static_cast<int>(j));
    }
  LaplacianCoordinates out;
  auto pattern = std::make_shared<BlockPattern>();
  pattern->columns = static_cast<int>(columns.size());
  out.ring_offsets_.assign(1, 0);
  for (int i : rows) {
    pattern->row_start.push_back(static_cast<int>(pattern->column.size()));
    pattern->column.push_back(local[self(i)]);
    const int first_block = block_pattern_->row_start[i];
    out.laplacian_blocks_.push_back(laplacian_blocks_[first_block]);
    for (int k = ring_offsets_[i]; k < ring_offsets_[i + 1]; ++k) {
      out.ring_.push_back(local[ring_[k]]);
      out.mu_.push_back(mu_[k]);
      pattern->column.push_back(local[ring_[k]]);
      out.laplacian_blocks_.push_back(laplacian_blocks_[first_block + 1 + (k - ring_offsets_[i])]);
    }
    out.ring_offsets_.push_back(static_cast<int>(out.ring_.size()));
    out.gamma_.push_back(gamma_[i]);
    out.d_floor_.push_back(d_floor_[i]);
    out.self_.push_back(local[self(i)]);
    out.boundary_.push_back(boundary_[i]);
  }
  pattern->row_start.push_back(static_cast<int>(pattern->column.size()));
  pattern->index_columns();
  out.block_pattern_ = std::move(pattern);
  return out;
}

void LaplacianCoordinates::ring_edges(const double* x, int i, std::vector<Eigen::Vector3d>& e) const {
  const int begin = ring_offsets_[i], k = ring_offsets_[i + 1] - begin;
  const double* own = x + 3 * static_cast<std::size_t>(self(i));
  const Eigen::Vector3d xi(own[0], own[1], own[2]);
  e.resize(k);
  for (int t = 0; t < k; ++t) {
    const double* xj = x + 3 * static_cast<std::size_t>(ring_[begin + t]);
    e[t] = Eigen::Vector3d(xj[0], xj[1], xj[2]) - xi;
  }
}

Eigen::Vector3d LaplacianCoordinates::direction_sum(const std::vector<Eigen::Vector3d>& e, int i) const {
  const int begin = ring_offsets_[i], k = static_cast<int>(e.size());
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (int t = 0; t < k; ++t) d += mu_[begin + t] * e[(t + k - 1) % k].cross(e[t]);
  return d;
}

double LaplacianCoordinates::delta_hat_scale(const Eigen::Vector3d& d, int i) const {
  // Clamping |d| from below keeps a collapsed one-ring finite (delta_hat_i -> 0 continuously there).
  const double denom = std::max(d.norm(), d_floor_[i]);
  return denom > 0.0 ? gamma_[i] / denom : 0.0;
}

Vertices LaplacianCoordinates::evaluate(const Vertices& X) const {
  check_rows(X);
  Vertices out(vertex_count(), 3);
  parallel::parallel_for(0, vertex_count(), kVertexBlock, [&](int lo, int hi) {
    std::vector<Eigen::Vector3d> e;
    for (int i = lo; i < hi; ++i) {
      ring_edges(X.data(), i, e);
      const Eigen::Vector3d d = direction_sum(e, i);
      out.row(i) = delta_hat_scale(d, i) * d.transpose();
    }
  });
  return out;
}

Vertices LaplacianCoordinates::laplacian_residual(const Vertices& X) const {
  check_rows(X);
  Vertices out(vertex_count(), 3);
  parallel::parallel_for(0, vertex_count(), kVertexBlock, [&](int lo, int hi) {
    std::vector<Eigen::Vector3d> e;
    for (int i = lo; i < hi; ++i) {
      ring_edges(X.data(), i, e);
      const double* ring_weights = &laplacian_blocks_[block_pattern_->row_start[i] + 1];  // slot 0 is L_ii
      Eigen::Vector3d lx = Eigen::Vector3d::Zero();
      for (size_t t = 0; t < e.size(); ++t) lx += ring_weights[t] * e[t];
      const Eigen::Vector3d d = direction_sum(e, i);
      out.row(i) = (lx - delta_hat_scale(d, i) * d).transpose();
    }
  });
  return out;
}

Eigen::SparseMatrix<double> LaplacianCoordinates::jacobian(const Vertices& X) const {
  BlockSparse3 J;
  jacobian_blocks(X, J);
  return J.to_sparse();
}

void LaplacianCoordinates::jacobian_blocks(const Vertices& X, BlockSparse3& J) const {
  DeltaHatJacobian factors;
  jacobian_factors(X, factors);
  if (!J.has_pattern(block_pattern_)) J = BlockSparse3(block_pattern_);
  const BlockPattern& p = *block_pattern_;
  for (int i = 0; i < p.vertex_count(); ++i)
    for (int k = p.row_start[i]; k < p.row_start[i + 1]; ++k) factors.block(i, k, 1.0, 0.0, J.block(k));
}

void LaplacianCoordinates::jacobian_factors(const Vertices& X, DeltaHatJacobian& J) const {
  check_rows(X);
  const int n = vertex_count();
  J.pattern = block_pattern_;
  J.c.resize(n);
  J.u.resize(3 * static_cast<std::size_t>(n));
  J.v.resize(3 * static_cast<std::size_t>(block_pattern_->block_count()));
  parallel::parallel_for(0, n, kVertexBlock, [&](int lo, int hi) {
    std::vector<Eigen::Vector3d> e;  // ring edges x_j - x_i
    for (int i = lo; i < hi; ++i) {
      const int begin = ring_offsets_[i], k = ring_offsets_[i + 1] - begin;
      ring_edges(X.data(), i, e);
      // docs/method.md section 4, in relative coordinates: for c = e_a x e_b (a = ring[t-1], b = ring[t]),
      // dc/dx_a = -[e_b]x, dc/dx_b = [e_a]x, dc/dx_i = [e_b - e_a]x; d_i sums mu_t c. Slot 0 of row i's blocks
      // is i itself, slot 1 + t is ring[t].
      Eigen::Map<Eigen::Matrix3Xd> v(&J.v[3 * static_cast<std::size_t>(begin + i)], 3, k + 1);
      v.setZero();
      for (int t = 0; t < k; ++t) {
        const int a = (t + k - 1) % k;
        const double m = mu_[begin + t];
        v.col(1 + a) -= m * e[t];
        v.col(1 + t) += m * e[a];
        v.col(0) += m * (e[t] - e[a]);
      }
      // d delta_hat_i / d d_i = c (I - u u^T) with c = gamma / |d| and u = d / |d| (the report's 3x3 matrix).
      // Below the floor delta_hat_i = gamma d / floor is linear in d (u = 0); with no floor (degenerate at
      // rest) delta_hat_i is identically zero (c = 0).
      const Eigen::Vector3d d = direction_sum(e, i);
      const double norm = d.norm();
      J.c[i] = delta_hat_scale(d, i);
      Eigen::Map<Eigen::Vector3d> u(&J.u[3 * static_cast<std::size_t>(i)]);
      if (norm > d_floor_[i] && norm > 0.0) u = d / norm;
      else u.setZero();
    }
  });
}

}  // namespace sd
