#include "core/solver/internal/energy/laplacian_rows.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "core/parallel/parallel_for.h"
#include "core/solver/internal/energy/laplacian_coordinates.h"

namespace sd {

void DeltaHatJacobian::block(int i, int k, double sign, double shift, double* out) const {
  const double* ui = &u[3 * static_cast<std::size_t>(i)];
  const double* w = &v[3 * static_cast<std::size_t>(k)];
  // (I - u u^T) [w]x = [w]x - u (u x w)^T.
  const double uw[3] = {ui[1] * w[2] - ui[2] * w[1], ui[2] * w[0] - ui[0] * w[2], ui[0] * w[1] - ui[1] * w[0]};
  const double skew[9] = {0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0};
  const double s = sign * c[static_cast<std::size_t>(i)];
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 3; ++col)
      out[3 * r + col] = s * (skew[3 * r + col] - ui[r] * uw[col]) + (r == col ? shift : 0.0);
}

namespace {

void check_rows(const Eigen::MatrixXd& x, int rows, const char* what) {
  if (x.rows() != rows || x.cols() % 3 != 0)
    throw Error(std::string(what) + ": a block of " + std::to_string(x.rows()) + " x " + std::to_string(x.cols()) +
                " (expected " + std::to_string(rows) + " rows by a multiple of 3)");
}

}  // namespace

// Vertices per task of the products (a few microseconds of work each at ~7 blocks per vertex).
constexpr int kVertexBlock = 512;

void LaplacianRows::linearize(const LaplacianCoordinates& coordinates, const Vertices& X) {
  coordinates.jacobian_factors(X, J_);
  order_by_column();
}

void LaplacianRows::leave_out_delta_hat() { std::fill(J_.c.begin(), J_.c.end(), 0.0); }

void LaplacianRows::order_by_column() {
  const BlockPattern& p = *J_.pattern;
  const double* L = laplacian_->data();
  const double* V = J_.v.data();
  by_column_.resize(4 * static_cast<std::size_t>(p.block_count()));
  parallel::parallel_for(0, p.column_count(), kVertexBlock, [&](int lo, int hi) {
    for (int e = p.column_start[lo]; e < p.column_start[hi]; ++e) {
      const std::size_t k = static_cast<std::size_t>(p.column_blocks[e]);
      double* b = &by_column_[4 * static_cast<std::size_t>(e)];
      b[0] = L[k];
      b[1] = V[3 * k];
      b[2] = V[3 * k + 1];
      b[3] = V[3 * k + 2];
    }
  });
}

Eigen::MatrixXd LaplacianRows::multiply(const Eigen::MatrixXd& x) const {
  const BlockPattern& p = *J_.pattern;
  check_rows(x, p.column_count(), "Jacobian rows product");
  const int n = p.vertex_count();
  const double* L = laplacian_->data();
  const double* V = J_.v.data();
  Eigen::MatrixXd out(n, x.cols());
  for (Eigen::Index t = 0; t < x.cols(); t += 3) {
    const double *x0 = x.col(t).data(), *x1 = x.col(t + 1).data(), *x2 = x.col(t + 2).data();
    double *o0 = out.col(t).data(), *o1 = out.col(t + 1).data(), *o2 = out.col(t + 2).data();
    parallel::parallel_for(0, n, kVertexBlock, [&](int lo, int hi) {  // row i writes out row i only
      for (int i = lo; i < hi; ++i) {
        double a0 = 0, a1 = 0, a2 = 0;  // sum_k L_ik y_k
        double w0 = 0, w1 = 0, w2 = 0;  // sum_k v_k x y_k
        for (int k = p.row_start[i]; k < p.row_start[i + 1]; ++k) {
          const int j = p.column[k];
          const double y0 = x0[j], y1 = x1[j], y2 = x2[j];
          const double* v = V + 3 * static_cast<std::size_t>(k);
          a0 += L[k] * y0;
          a1 += L[k] * y1;
          a2 += L[k] * y2;
          w0 += v[1] * y2 - v[2] * y1;
          w1 += v[2] * y0 - v[0] * y2;
          w2 += v[0] * y1 - v[1] * y0;
        }
        const double* u = &J_.u[3 * static_cast<std::size_t>(i)];
        const double c = J_.c[i], uw = u[0] * w0 + u[1] * w1 + u[2] * w2;
        o0[i] = a0 - c * (w0 - u[0] * uw);
        o1[i] = a1 - c * (w1 - u[1] * uw);
        o2[i] = a2 - c * (w2 - u[2] * uw);
      }
    });
  }
  return out;
}

Eigen::MatrixXd LaplacianRows::multiply_transpose(const Eigen::MatrixXd& x) const {
  const BlockPattern& p = *J_.pattern;
  check_rows(x, p.vertex_count(), "Jacobian rows transposed product");
  if (p.column_start.empty()) throw Error("Jacobian rows transposed product: the pattern has no column index");
  const int n = p.vertex_count(), columns = p.column_count();
  if (by_column_.size() != 4 * static_cast<std::size_t>(p.block_count()))
    throw Error("Jacobian rows transposed product: the rows were not linearised");
  const double* B = by_column_.data();
  Eigen::MatrixXd out(columns, x.cols());
  Eigen::MatrixXd q(n, 3);  // q_i = c_i (I - u_i u_i^T) z_i
  for (Eigen::Index t = 0; t < x.cols(); t += 3) {
    const double *x0 = x.col(t).data(), *x1 = x.col(t + 1).data(), *x2 = x.col(t + 2).data();
    double *o0 = out.col(t).data(), *o1 = out.col(t + 1).data(), *o2 = out.col(t + 2).data();
    double *q0 = q.col(0).data(), *q1 = q.col(1).data(), *q2 = q.col(2).data();
    parallel::parallel_for(0, n, kVertexBlock, [&](int lo, int hi) {
      for (int i = lo; i < hi; ++i) {
        const double z0 = x0[i], z1 = x1[i], z2 = x2[i];
        const double* u = &J_.u[3 * static_cast<std::size_t>(i)];
        const double c = J_.c[i], uz = u[0] * z0 + u[1] * z1 + u[2] * z2;
        q0[i] = c * (z0 - u[0] * uz);
        q1[i] = c * (z1 - u[1] * uz);
        q2[i] = c * (z2 - u[2] * uz);
      }
    });
    // (M^T z)_j gathers the blocks (i, j) of column j by increasing i: the order in which a serial loop
    // over the rows would add them, so threads split the vertices without changing a bit.
    parallel::parallel_for(0, columns, kVertexBlock, [&](int lo, int hi) {
      for (int j = lo; j < hi; ++j) {
        double s0 = 0, s1 = 0, s2 = 0;
        for (int e = p.column_start[j]; e < p.column_start[j + 1]; ++e) {
          const int i = p.column_rows[e];
          const double* b = B + 4 * static_cast<std::size_t>(e);  // L_ij, then v
          s0 += b[0] * x0[i] + b[2] * q2[i] - b[3] * q1[i];
          s1 += b[0] * x1[i] + b[3] * q0[i] - b[1] * q2[i];
          s2 += b[0] * x2[i] + b[1] * q1[i] - b[2] * q0[i];
        }
        o0[j] = s0;
        o1[j] = s1;
        o2[j] = s2;
      }
    });
  }
  return out;
}

Eigen::SparseMatrix<double> LaplacianRows::to_sparse() const {
  const BlockPattern& p = *J_.pattern;
  BlockSparse3 blocks(J_.pattern);
  for (int i = 0; i < p.vertex_count(); ++i)
    for (int k = p.row_start[i]; k < p.row_start[i + 1]; ++k) J_.block(i, k, -1.0, (*laplacian_)[k], blocks.block(k));
  return blocks.to_sparse();
}

}  // namespace sd
