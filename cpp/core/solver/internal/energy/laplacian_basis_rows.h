// Rows of S L W, the Laplacian of the energy applied to the basis (n by m, as large as W, so never held whole):
// the subspace step's B = (S L W)^T (S L W) and the rotation clusters' D_c (rotation_clusters.h) are both summed
// from blocks of them.
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/basis/basis_matrix.h"

namespace sd {

// out += s * W.row(j) (m entries), reading W's storage directly (float32 or float64).
void add_scaled_row(const BasisMatrix& W, int j, double s, double* out);

// Rows [r0, r0 + rows) of L W, rows by m.
Eigen::MatrixXd laplacian_rows_times_w(const Eigen::SparseMatrix<double, Eigen::RowMajor>& L, const BasisMatrix& W,
                                       int r0, int rows);

}  // namespace sd
