// W_s^T W_s for the rows i = 0, stride, 2 stride, ... of W (all rows with stride 1): how much each cage
// motion moves the mesh, |W v|^2 = v^T W^T W v. Used by the cage quality (sampled rows) and the cage
// regularisation of the subspace solver (all rows). Fixed blocks of rows summed in block order, so the result
// does not depend on the number of threads.
#pragma once

#include <Eigen/Core>

#include "core/basis/basis_matrix.h"

namespace sd {

// m by m; `rows` sampled rows (at most ceil(n / stride)).
Eigen::MatrixXd basis_gram(const BasisMatrix& W, int stride, int rows);

}  // namespace sd
