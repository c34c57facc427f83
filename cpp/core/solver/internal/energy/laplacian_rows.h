// The Laplacian rows of the energy's Jacobian, M = L (x) I3 - J_delta_hat (deformation_energy.h), kept in
// factored form instead of as 3x3 blocks.
//
// Row block i of J_delta_hat (docs/method.md section 4, the chain rule through d/|d|) is
//   c_i (I - u_i u_i^T) [v_ik]x   for the blocks k of the one-ring pattern (the vertex i, then its ring),
// with u_i = d_i / |d_i|, c_i = gamma_i / |d_i| and [v]x the cross-product matrix. So
//   (M y)_i   = sum_k L_ik y_k - c_i (I - u_i u_i^T) sum_k v_ik x y_k,
//   (M^T z)_j = sum over the blocks (i, j): L_ij z_i + v_ij x q_i,   q_i = c_i (I - u_i u_i^T) z_i.
// Per block that is one index, one Laplacian entry and three numbers (v) instead of nine, so assembling it
// writes a third of the memory and each product reads half as much as a 3x3 block matrix did (the products
// stream these arrays: bar-fine's 43k vertices have 300k blocks).
//
// Vectors are #V by 3s blocks (column-major: columns 3t .. 3t+2 are x, y, z of vector t), the layout of the
// solver files.
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <memory>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/solver/internal/steps/block_sparse3.h"

namespace sd {

class LaplacianCoordinates;

// d delta_hat / d X at one point, factored as above (written by LaplacianCoordinates::jacobian_factors).
struct DeltaHatJacobian {
  std::shared_ptr<const BlockPattern> pattern;
  std::vector<double> c;  // per vertex
  std::vector<double> u;  // per vertex, 3 (zero where delta_hat_i is linear in d_i: below the |d| floor)
  std::vector<double> v;  // per block, 3
  // Block k (of row i) as a row-major 3x3 matrix: sign * c_i (I - u_i u_i^T) [v_k]x + shift I.
  void block(int i, int k, double sign, double shift, double* out) const;
};

class LaplacianRows {
 public:
  LaplacianRows() = default;
  // laplacian[k] = L_ij for block k = (i, j) of the pattern; kept by reference (it must outlive this).
  explicit LaplacianRows(const std::vector<double>* laplacian) : laplacian_(laplacian) {}

  // Linearises at X (J_delta_hat there, from `coordinates`, whose laplacian blocks these rows hold), rewriting
  // the factors in place (their storage is reused).
  void linearize(const LaplacianCoordinates& coordinates, const Vertices& X);
  // Leaves J_delta_hat out: the rows become L (x) I3.
  void leave_out_delta_hat();
  const DeltaHatJacobian& delta_hat_jacobian() const { return J_; }

  // M x for a (columns) by 3s block x and M^T z for a (rows) by 3s block z: #V by 3s both, unless the pattern
  // holds some rows only (BlockPattern::columns).
  Eigen::MatrixXd multiply(const Eigen::MatrixXd& x) const;
  Eigen::MatrixXd multiply_transpose(const Eigen::MatrixXd& x) const;
  // As an Eigen sparse matrix (interleaved index 3 * vertex + axis): for exact modes and tests.
  Eigen::SparseMatrix<double> to_sparse() const;

 private:
  // Copies L_ij and v of every block into by_column_ in the column order of the pattern.
  void order_by_column();

  const std::vector<double>* laplacian_ = nullptr;
  DeltaHatJacobian J_;
  // Per block in the order of BlockPattern::column_blocks: L_ij, then v (4 doubles). The transposed product
  // gathers each output vertex's blocks; read through column_blocks they lie all over the row-ordered arrays, and
  // on the boy (280k blocks, vertices not in spatial order) that product took 7.4 ms against 1.2 ms for the
  // forward one. Streamed from this copy it takes 1.6 ms, and the copy, made once per linearisation, 0.4 ms.
  std::vector<double> by_column_;
};

}  // namespace sd
