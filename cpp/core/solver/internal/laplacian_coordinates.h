// Rotation-invariant Laplacian coordinates delta_hat(X) (Huang et al. 2006;
// docs/method.md section 4). For vertex i with one-ring j_1..j_k ordered as the outward faces are:
//   c_ij(X) = (x_{j-1} - x_i) x (x_j - x_i),  d_i(X) = sum_j mu_ij c_ij(X),
//   delta_hat_i(X) = gamma_i d_i(X) / |d_i(X)|.
// mu_i is the minimum-norm solution of sum_j mu_ij c_ij(X0) = delta_i (delta = L X0) and
// gamma_i = |delta_i|, so delta_hat(X0) = L X0 exactly. Where that is ill-posed (|delta_i| ~ 0 or the
// solve leaves a residual) mu_ij = 1 and gamma_i = the signed component of delta_i along d_i(X0); such
// vertices are counted in fallback_count(). Throws sd::Error when a one-ring cannot be ordered (boundary,
// non-manifold or inconsistently oriented mesh).
// Flattened vectors and Jacobians use index 3 * vertex + axis (Vertices is row-major).
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <vector>

#include "core/solver/internal/block_sparse3.h"
#include "core/solver/internal/laplacian_rows.h"
#include "core/mesh/mesh.h"

namespace sd {

class LaplacianCoordinates {
 public:
  // X0, F: rest mesh (closed, manifold, outward). L: its cotangent Laplacian.
  LaplacianCoordinates(const Vertices& X0, const Faces& F, const Eigen::SparseMatrix<double>& L);
  LaplacianCoordinates() = default;  // no rows

  // The same terms for some rows only (sampled vertices, in the order given, distinct), against the vertices they
  // touch: the columns of the result are `columns` (global indices: the rows and their one-rings, increasing).
  // Every method below then takes positions of those columns only and returns values for those rows: the
  // reduced integration of the solver evaluates a few hundred vertices this way (cubature.h).
  LaplacianCoordinates restricted(const std::vector<int>& rows, std::vector<int>& columns) const;

  // delta_hat(X), #V by 3.
  Vertices evaluate(const Vertices& X) const;
  // L X - delta_hat(X), #V by 3, in one pass over the one-rings: (L X)_i = sum_j L_ij (x_j - x_i) (L 1 = 0)
  // from the same edge vectors that d_i is made of. The energy's Laplacian residual.
  Vertices laplacian_residual(const Vertices& X) const;

  // J = d delta_hat / d X at X (docs/method.md section 4, the chain rule through d/|d|): 3#V by 3#V, sparse.
  Eigen::SparseMatrix<double> jacobian(const Vertices& X) const;
  // The same as 3x3 blocks on block_pattern(), written into J.
  void jacobian_blocks(const Vertices& X, BlockSparse3& J) const;
  // The same in factored form (laplacian_rows.h), written into J (its storage is reused: the solver's
  // once-per-iteration path).
  void jacobian_factors(const Vertices& X, DeltaHatJacobian& J) const;
  // Row block i: the blocks of columns i (first) and of the one-ring of i, in one_ring order.
  const std::shared_ptr<const BlockPattern>& block_pattern() const { return block_pattern_; }
  // L_ij of the cotangent Laplacian for each block (i, j) of block_pattern() (L_ii first in each row).
  const std::vector<double>& laplacian_blocks() const { return laplacian_blocks_; }

  int fallback_count() const { return fallback_count_; }
  int vertex_count() const { return static_cast<int>(ring_offsets_.size()) - 1; }  // rows
  int column_count() const { return block_pattern_->column_count(); }

  // The column of row i's own vertex (i itself unless restricted).
  int own_column(int i) const { return self(i); }
  // One-ring of vertex i in the order of the outward faces, so that element t and its predecessor
  // (cyclically) span the outward triangle (i, ring[t-1], ring[t]).
  std::vector<int> one_ring(int i) const {
    return {ring_.begin() + ring_offsets_[i], ring_.begin() + ring_offsets_[i + 1]};
  }

 private:
  // The column of row i's own vertex (i itself unless restricted).
  int self(int i) const { return self_.empty() ? i : self_[i]; }
  // The edge vectors x_j - x_i of the one-ring of i (x: row-major positions), into e.
  void ring_edges(const double* x, int i, std::vector<Eigen::Vector3d>& e) const;
  // d_i = sum_t mu_t (e_{t-1} x e_t) from the ring edges.
  Eigen::Vector3d direction_sum(const std::vector<Eigen::Vector3d>& e, int i) const;
  // delta_hat_i = this times d_i: gamma_i / |d_i|, with |d_i| clamped below at its floor (0 without one).
  double delta_hat_scale(const Eigen::Vector3d& d, int i) const;
  void check_rows(const Vertices& X) const;

  // One-ring of vertex i: ring_[ring_offsets_[i] .. ring_offsets_[i+1]), ordered as the outward faces.
  std::vector<int> ring_offsets_;
  std::vector<int> ring_;
  std::vector<double> mu_;  // parallel to ring_
  std::vector<double> laplacian_blocks_;  // L_ij per block of block_pattern_
  std::vector<double> gamma_;
  // |d_i| is clamped below at d_floor_[i] (a tiny fraction of its rest magnitude) so that a one-ring
  // collapsed by a deformation gives a finite delta_hat_i and Jacobian instead of NaN.
  std::vector<double> d_floor_;
  int fallback_count_ = 0;
  std::vector<int> self_;  // restricted rows only: each row's own column
  // Block (i, j) of the Jacobian is nonzero for j = i or j in the one-ring of i: row i's blocks start at
  // ring_offsets_[i] + i (slot 0 is i itself, slots 1..k its ring).
  std::shared_ptr<const BlockPattern> block_pattern_;
};

}  // namespace sd
