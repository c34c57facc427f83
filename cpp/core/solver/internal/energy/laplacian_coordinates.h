// Rotation-invariant Laplacian coordinates delta_hat(X) (Huang et al. 2006;
// docs/method.md section 4). For vertex i with one-ring j_1..j_k ordered as the outward faces are:
//   c_ij(X) = (x_{j-1} - x_i) x (x_j - x_i),  d_i(X) = sum_j mu_ij c_ij(X),
//   delta_hat_i(X) = gamma_i d_i(X) / |d_i(X)|.
// mu_i is the minimum-norm solution of sum_j mu_ij c_ij(X0) = delta_i (delta = L X0) and
// gamma_i = |delta_i|, so delta_hat(X0) = L X0 exactly. Where that is ill-posed (|delta_i| ~ 0 or the
// solve leaves a residual) mu_ij = 1 and gamma_i = the signed component of delta_i along d_i(X0); such
// vertices are counted in fallback_count(). Throws sd::Error when a one-ring cannot be ordered (a non-manifold
// vertex or edge, or an inconsistently oriented mesh).
//
// Open meshes. A boundary vertex's triangles form an open fan (i, j_0, j_1), .., (i, j_{k-1}, j_k): its ring is
// j_0 .. j_k, and the slot of the missing triangle (i, j_k, j_0) has mu = 0, so d_i sums over the existing faces
// only. Its delta_i = (L X0)_i has a large tangential part (the rim pulls inward), which no combination of face
// normals can produce; so d_i is the area-weighted normal (mu = 1), gamma_i = delta_i . d_i / |d_i|, and the
// tangential rest the normals miss, t_i = delta_i - gamma_i d_i / |d_i|, moves into row i of the energy's
// Laplacian as a fixed combination of the ring's edges: L'_ij = L_ij - nu_j with sum_j nu_j (x0_j - x0_i) = t_i
// (minimum-norm nu). Then L' X0 = delta_hat(X0) holds exactly at every vertex (the rest pose stays a fixed
// point), row i stays linear with zero sum, and the rest turns with the ring like every other term.
// laplacian() is that L' (= L on a closed mesh): the energy uses it in place of L (docs/method.md section 4).
// Flattened vectors and Jacobians use index 3 * vertex + axis (Vertices is row-major).
#pragma once

#include <Eigen/Sparse>
#include <algorithm>
#include <memory>
#include <vector>

#include "core/solver/internal/steps/block_sparse3.h"
#include "core/solver/internal/energy/laplacian_rows.h"
#include "core/mesh/mesh.h"

namespace sd {

class LaplacianCoordinates {
 public:
  // X0, F: rest mesh (edge- and vertex-manifold, consistently oriented, open or closed). L: its cotangent
  // Laplacian.
  LaplacianCoordinates(const Vertices& X0, const Faces& F, const Eigen::SparseMatrix<double>& L);
  LaplacianCoordinates() = default;  // no rows

  // The same terms for some rows only (sampled vertices, in the order given, distinct), against the vertices they
  // touch: the columns of the result are `columns` (global indices: the rows and their one-rings, increasing).
  // Every method below then takes positions of those columns only and returns values for those rows: the
  // reduced integration of a small mesh evaluates its vertices this way (sampled_laplacian.h).
  LaplacianCoordinates restricted(const std::vector<int>& rows, std::vector<int>& columns) const;

  // The Laplacian of the energy's rows: L with the boundary vertices' rows adjusted (see above); L itself for
  // a closed mesh.
  Eigen::SparseMatrix<double> laplacian() const;

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
  // Vertices on the boundary of an open mesh (their one-rings are open fans).
  int boundary_count() const { return static_cast<int>(std::count(boundary_.begin(), boundary_.end(), 1)); }
  bool is_boundary(int i) const { return boundary_[i] != 0; }

  // The column of row i's own vertex (i itself unless restricted).
  int own_column(int i) const { return self(i); }
  // One-ring of vertex i in the order of the outward faces, so that element t and its predecessor
  // (cyclically) span the outward triangle (i, ring[t-1], ring[t]); on a boundary vertex element 0 is the
  // first neighbour of the open fan, and the pair (ring[k-1], ring[0]) spans no triangle.
  std::vector<int> one_ring(int i) const {
    return {ring_.begin() + ring_offsets_[i], ring_.begin() + ring_offsets_[i + 1]};
  }

 private:
  // Constructor steps: the one-rings in the order of the outward faces, the block pattern, L_ij per block,
  // then the rest fit of each vertex (closed one-ring or open fan).
  void order_one_rings(const Faces& F, int n);
  void build_block_pattern(int n);
  void copy_laplacian_blocks(const Eigen::SparseMatrix<double>& L);
  void fit_rest_pose(const Vertices& X0, const Vertices& delta, const Eigen::SparseMatrix<double>& L);
  // Fits vertex i; returns false when it used the fallback.
  bool fit_closed_vertex(const Vertices& X0, const Eigen::Vector3d& delta, const Eigen::SparseMatrix<double>& L, int i);
  bool fit_boundary_vertex(const Vertices& X0, const Eigen::Vector3d& delta, int i);
  void set_norm_floor(const Vertices& X0, int i);

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
  std::vector<double> mu_;                // parallel to ring_
  std::vector<double> laplacian_blocks_;  // L_ij per block of block_pattern_
  std::vector<double> gamma_;
  // |d_i| is clamped below at d_floor_[i] (a tiny fraction of its rest magnitude) so that a one-ring
  // collapsed by a deformation gives a finite delta_hat_i and Jacobian instead of NaN.
  std::vector<double> d_floor_;
  int fallback_count_ = 0;
  std::vector<char> boundary_;  // 1: vertex i's triangles form an open fan
  std::vector<int> self_;       // restricted rows only: each row's own column
  // Block (i, j) of the Jacobian is nonzero for j = i or j in the one-ring of i: row i's blocks start at
  // ring_offsets_[i] + i (slot 0 is i itself, slots 1..k its ring).
  std::shared_ptr<const BlockPattern> block_pattern_;
};

}  // namespace sd
