// Solves a sparse factorization (Eigen's SimplicialLDLT/LLT) for each column of a dense right-hand side on
// its own thread. The triangular solves are sequential within a column, so the columns (x, y, z of the
// solver's blocks) are the parallelism they have; each column's result is the same bits as a serial solve.
#pragma once

#include <Eigen/Core>

#include "core/parallel/thread_pool.h"

namespace sd::parallel {

template <typename Factorization, typename Rhs>
Eigen::Matrix<double, Eigen::Dynamic, Rhs::ColsAtCompileTime> solve_columns(const Factorization& factor,
                                                                            const Rhs& rhs) {
  Eigen::Matrix<double, Eigen::Dynamic, Rhs::ColsAtCompileTime> out(rhs.rows(), rhs.cols());
  run_tasks(static_cast<int>(rhs.cols()), [&](int c) { out.col(c) = factor.solve(rhs.col(c)); });
  return out;
}

}  // namespace sd::parallel
