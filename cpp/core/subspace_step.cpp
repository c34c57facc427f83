#include "core/subspace_step.h"

#include <chrono>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Sparse>

#include "core/batched_pcg.h"
#include "core/error.h"

namespace sd {
namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// out += s * W.row(j), reading W's storage directly (float32 or float64).
void add_scaled_row(const WeightMatrix& W, int j, double s, double* out) {
  const int m = W.cols();
  if (W.single_precision()) {
    const float* row = static_cast<const float*>(W.data()) + static_cast<std::size_t>(j) * m;
    for (int k = 0; k < m; ++k) out[k] += s * static_cast<double>(row[k]);
  } else {
    const double* row = static_cast<const double*>(W.data()) + static_cast<std::size_t>(j) * m;
    for (int k = 0; k < m; ++k) out[k] += s * row[k];
  }
}

// Rows [r0, r0 + rows) of L W, rows by m.
Eigen::MatrixXd laplacian_rows_times_w(const Eigen::SparseMatrix<double, Eigen::RowMajor>& L, const WeightMatrix& W,
                                       int r0, int rows) {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> out =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>::Zero(rows, W.cols());
  for (int i = 0; i < rows; ++i)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(L, r0 + i); it; ++it)
      add_scaled_row(W, static_cast<int>(it.col()), it.value(), out.row(i).data());
  return out;
}

// Columns 3k + axis (k = 0..#V-1) of an interleaved 3#V by 3#V matrix: 3#V by #V.
Eigen::SparseMatrix<double> axis_columns(const Eigen::SparseMatrix<double>& J, int axis) {
  const Eigen::Index n = J.cols() / 3;
  Eigen::SparseMatrix<double> out(J.rows(), n);
  out.reserve(J.nonZeros() / 3 + n);
  for (Eigen::Index k = 0; k < n; ++k) {
    out.startVec(k);
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, 3 * k + axis); it; ++it) out.insertBack(it.row(), k) = it.value();
  }
  out.finalize();
  return out;
}

Eigen::VectorXd flat(const Eigen::MatrixXd& block) { return Eigen::Map<const Eigen::VectorXd>(block.data(), block.size()); }
Eigen::MatrixXd unflat(const Eigen::VectorXd& v, Eigen::Index m) { return Eigen::Map<const Eigen::MatrixXd>(v.data(), m, 3); }

}  // namespace

SubspaceStep::SubspaceStep(const DeformationEnergy& energy, const WeightMatrix& W) : energy_(&energy), W_(&W) {
  const double t0 = now_ms();
  const int n = W.rows(), m = W.cols();
  if (n != energy.vertex_count())
    throw Error("subspace: W has " + std::to_string(n) + " rows for a mesh of " +
                std::to_string(energy.vertex_count()) + " vertices");
  // B = (L W)^T (L W) by blocks of rows, so L W (as large as W) is never held whole.
  const Eigen::SparseMatrix<double, Eigen::RowMajor> L = energy.laplacian();
  B_ = Eigen::MatrixXd::Zero(m, m);
  const int chunk = 512;
  for (int r0 = 0; r0 < n; r0 += chunk) {
    const int rows = std::min(chunk, n - r0);
    const Eigen::MatrixXd LWc = laplacian_rows_times_w(L, W, r0, rows);
    B_.selfadjointView<Eigen::Lower>().rankUpdate(LWc.transpose());
  }
  B_ = B_.selfadjointView<Eigen::Lower>();
  precompute_ms_ = now_ms() - t0;
}

void SubspaceStep::refactor(const DeformationEnergy& energy) {
  const double t0 = now_ms();
  const auto& handles = energy.handle_vertices();
  if (handles.empty()) {  // N = B is singular (W 1 = 1 and L 1 = 0): nothing to solve without handles
    factored_ = false;
    return;
  }
  const int m = W_->cols();
  Eigen::MatrixXd Wh = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(handles.size()), m);
  for (size_t k = 0; k < handles.size(); ++k)
    for (int j = 0; j < m; ++j) Wh(static_cast<Eigen::Index>(k), j) = W_->get(handles[k], j);
  const double w = energy.position_weight();
  Eigen::MatrixXd N = B_;
  N.noalias() += (w * w) * Wh.transpose() * Wh;
  Eigen::LLT<Eigen::MatrixXd> factor(N);
  if (factor.info() != Eigen::Success || !factor.matrixLLT().allFinite())
    throw Error("subspace: the preconditioner N = W^T (L^T L + w^2 Phi^T Phi) W (" + std::to_string(m) + " x " +
                std::to_string(m) + ") is not positive definite; the cage coordinates W may be rank-deficient "
                "or the position weight is not positive");
  N_ = std::move(factor);
  factored_ = true;
  factor_ms_ = now_ms() - t0;
}

Eigen::MatrixXd SubspaceStep::gradient(const EnergyJacobian& J, const EnergyEvaluation& e) const {
  Eigen::MatrixXd out;
  W_->multiply_transpose(J.gradient(e), out);
  return out;
}

Eigen::MatrixXd SubspaceStep::precondition(const Eigen::MatrixXd& R) const {
  if (!factored_) throw Error("subspace: no handles are set, so the step is undefined");
  return N_.solve(R);
}

Eigen::MatrixXd SubspaceStep::product(const EnergyJacobian& J, const Eigen::MatrixXd& V, Eigen::MatrixXd& image) const {
  W_->multiply(V, image);
  const Eigen::MatrixXd Z = J.normal_product(image);
  Eigen::MatrixXd out;
  W_->multiply_transpose(Z, out);
  return out;
}

const Eigen::MatrixXd& SubspaceStep::laplacian_times_w() const {
  if (LW_.size() == 0) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> L = energy_->laplacian();
    LW_ = laplacian_rows_times_w(L, *W_, 0, W_->rows());
  }
  return LW_;
}

Eigen::MatrixXd SubspaceStep::dense_jacobian(const EnergyJacobian& J, double memory_budget_bytes) const {
  const Eigen::Index n = W_->rows(), m = W_->cols();
  const auto& handles = energy_->handle_vertices();
  const Eigen::Index k = static_cast<Eigen::Index>(handles.size());
  const double bytes = 8.0 * (double(3 * n + 3 * k) * double(3 * m) + 2.0 * double(n) * double(m));
  if (bytes > memory_budget_bytes) {
    std::ostringstream message;
    message << "exact mode needs " << static_cast<long long>(bytes / 1e6) << " MB for the dense subspace Jacobian ("
            << 3 * n << " x " << 3 * m << "), more than the budget of " << static_cast<long long>(memory_budget_bytes / 1e6)
            << " MB; use the fast mode";
    throw Error(message.str());
  }
  if (W_dense_.size() == 0) W_dense_ = W_->to_dense();
  const Eigen::MatrixXd& LW = laplacian_times_w();
  const Eigen::SparseMatrix<double>& Jd = J.delta_hat_jacobian();
  Eigen::MatrixXd JW = Eigen::MatrixXd::Zero(3 * n + 3 * k, 3 * m);
  for (int axis = 0; axis < 3; ++axis) {
    auto block = JW.block(0, axis * m, 3 * n, m);
    block.noalias() -= axis_columns(Jd, axis) * W_dense_;
    for (Eigen::Index i = 0; i < n; ++i) block.row(3 * i + axis) += LW.row(i);
    const double w = energy_->position_weight();
    for (Eigen::Index h = 0; h < k; ++h) JW.block(3 * n + 3 * h + axis, axis * m, 1, m) = w * W_dense_.row(handles[h]);
  }
  return JW;
}

ConstrainedStep SubspaceStep::compute(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                                      const SolverOptions& options) {
  if (!factored_) throw Error("subspace: no handles are set, so the step is undefined");
  const int m = W_->cols();
  const bool volume = options.volume;
  // One transposed pass serves the gradient and the volume right-hand side.
  Eigen::MatrixXd G(X.rows(), volume ? 6 : 3);
  G.leftCols(3) = J.gradient(e);
  if (volume) G.rightCols(3) = energy_->volume_gradient(X);
  Eigen::MatrixXd bc;
  W_->multiply_transpose(G, bc);
  const Eigen::MatrixXd b = bc.leftCols(3);
  const Eigen::MatrixXd c = volume ? Eigen::MatrixXd(bc.rightCols(3)) : Eigen::MatrixXd::Zero(m, 3);
  ConstrainedStep step = options.jacobian == JacobianMode::Exact ? exact_step(J, b, c, e.constraint, volume, options)
                                                                 : fast_step(J, b, c, e.constraint, volume, options);
  step.passes += 1;
  return step;
}

ConstrainedStep SubspaceStep::exact_step(const EnergyJacobian& J, const Eigen::MatrixXd& b, const Eigen::MatrixXd& c,
                                         double g, bool volume, const SolverOptions& options) const {
  const int m = W_->cols();
  ConstrainedStep step;
  const Eigen::MatrixXd JW = dense_jacobian(J, options.exact_memory_budget_bytes);
  Eigen::MatrixXd A(3 * m, 3 * m);
  A.setZero();
  A.selfadjointView<Eigen::Lower>().rankUpdate(JW.transpose());
  A = A.selfadjointView<Eigen::Lower>();
  // Pivoted LDLT: robust when A is only semidefinite (a single handle vertex at rest leaves a rotation free).
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive())
    throw Error("exact subspace step: the normal matrix (J_f W)^T (J_f W) could not be factored");
  Eigen::MatrixXd rhs(3 * m, volume ? 2 : 1);
  rhs.col(0) = flat(b);
  if (volume) rhs.col(1) = flat(c);
  const Eigen::MatrixXd sol = ldlt.solve(rhs);
  const Eigen::MatrixXd u = unflat(sol.col(0), m);
  const Eigen::MatrixXd v = volume ? unflat(sol.col(1), m) : Eigen::MatrixXd();
  step.lambda = volume ? volume_multiplier(u, v, c, g) : 0.0;
  step.du = volume ? Eigen::MatrixXd(-(u + step.lambda * v)) : Eigen::MatrixXd(-u);
  step.slope = block_dot(step.du, b + step.lambda * c);
  // One forward pass maps the step and the restoration direction N^-1 c.
  Eigen::MatrixXd D(m, volume ? 6 : 3), image;
  D.leftCols(3) = step.du;
  if (volume) D.rightCols(3) = N_.solve(c);
  W_->multiply(D, image);
  step.passes += 1;
  step.dx = image.leftCols(3);
  if (volume) {
    step.restore_du = D.rightCols(3);
    step.restore_dx = image.rightCols(3);
  }
  return step;
}

ConstrainedStep SubspaceStep::fast_step(const EnergyJacobian& J, const Eigen::MatrixXd& b, const Eigen::MatrixXd& c,
                                        double g, bool volume, const SolverOptions& options) const {
  const int m = W_->cols();
  ConstrainedStep step;
  PcgOperator op;
  op.apply = [&](const Eigen::MatrixXd& P, Eigen::MatrixXd& AP, Eigen::MatrixXd& image) { AP = product(J, P, image); };
  op.precondition = [&](const Eigen::MatrixXd& R) { return N_.solve(R); };
  // Near the constrained minimum b ~ -lambda c, so u = A^-1 b and lambda v nearly cancel and each
  // inexact solve's error would swamp h. Solve instead for the shifted right-hand side b + lambda0 c,
  // with lambda0 the least-squares multiplier in the N^-1 metric (no pass over W), which tends to 0 as
  // the iteration converges; the correction of lambda then multiplies v by a vanishing amount too.
  const double lambda0 = volume ? -block_dot(c, N_.solve(b)) / block_dot(c, N_.solve(c)) : 0.0;
  const Eigen::MatrixXd r = b + lambda0 * c;
  Eigen::MatrixXd rhs(m, volume ? 6 : 3);
  rhs.leftCols(3) = r;
  if (volume) rhs.rightCols(3) = c;
  BatchedPcg pcg(op, rhs, W_->rows());
  auto solve_to = [&](double tolerance) {
    if (volume) pcg.run_until(combined_step_converged(rhs, c, g, tolerance), options.cg_max_iterations);
    else pcg.run(tolerance, options.cg_max_iterations);
  };
  solve_to(options.cg_tolerance);

  auto assemble = [&](const Eigen::MatrixXd& x, const Eigen::MatrixXd& image) {
    const Eigen::MatrixXd u = x.leftCols(3);
    const Eigen::MatrixXd v = volume ? Eigen::MatrixXd(x.rightCols(3)) : Eigen::MatrixXd();
    const double correction = volume ? volume_multiplier(u, v, c, g) : 0.0;
    step.lambda = lambda0 + correction;
    step.du = -u;
    step.dx = -image.leftCols(3);
    if (volume) {
      step.du -= correction * v;
      step.dx -= correction * image.rightCols(3);
    }
    step.slope = block_dot(step.du, b + step.lambda * c);
  };
  assemble(pcg.x(), pcg.image());
  const bool moving = step.du.squaredNorm() > 0.0;
  if (moving && !(step.slope < 0.0)) {
    // The inexact solves combined into a non-descent direction (rare, near convergence): solve tighter.
    solve_to(options.cg_tolerance * 1e-3);
    assemble(pcg.x(), pcg.image());
  }
  if (moving && !(step.slope < 0.0)) {
    // Last resort: the preconditioned gradient step, with its own multiplier so that c.h = -g still
    // holds; it is a descent direction of its merit because N is positive definite.
    step.fallbacks = 1;
    assemble(pcg.first_direction(), pcg.first_direction_image());
  }
  step.inner_iterations = pcg.products();
  step.products = pcg.products();
  step.passes = 2 * pcg.products();
  if (volume) {
    step.restore_du = pcg.first_direction().rightCols(3);  // N^-1 c: the first search direction of the c-solve
    if (pcg.first_image_valid(1)) {
      step.restore_dx = pcg.first_direction_image().rightCols(3);
    } else {
      W_->multiply(step.restore_du, step.restore_dx);
      step.passes += 1;
    }
  }
  return step;
}

}  // namespace sd
