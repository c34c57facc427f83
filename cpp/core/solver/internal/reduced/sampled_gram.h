// The Gauss-Newton matrix of some rows of the Laplacian term in the subspace: sum over rows s of
// w_s (M_s W_S (x) I3)^T (M_s W_S (x) I3), 3m x 3m (index axis * m + cage vertex), for rows M (laplacian_rows.h)
// restricted to a set of vertices (their one-rings' rows of W: W_S). The reduced integration's dense matrix
// (its samples) and the factor preconditioner's rotation terms (the stiff vertices) are both made by it.
#pragma once

#include <Eigen/Core>

#include "core/solver/internal/energy/laplacian_rows.h"

namespace sd {

// O(rows m^2); fixed blocks of rows, so the result does not depend on the thread count.
Eigen::MatrixXd sampled_gram(const LaplacianRows& M, const Eigen::MatrixXd& W_local, const Eigen::VectorXd& weights);

}  // namespace sd
