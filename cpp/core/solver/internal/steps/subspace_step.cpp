#include "core/solver/internal/steps/subspace_step.h"

#include "core/solver/internal/constraints/hard_constraints.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Sparse>

#include "core/solver/internal/constraints/hard_constraints.h"
#include "core/solver/internal/energy/laplacian_basis_rows.h"
#include "core/solver/internal/steps/pcg_step.h"
#include "core/solver/internal/steps/projected_pcg.h"
#include "core/solver/internal/steps/row_gram.h"
#include "core/error.h"
#include "core/timer.h"
#include "core/parallel/parallel_for.h"
#include "core/basis/basis_gram.h"

namespace sd {
namespace {

// Columns 3k + axis (k = 0..#V-1) of an interleaved 3#V by 3#V matrix: 3#V by #V.
Eigen::SparseMatrix<double> axis_columns(const Eigen::SparseMatrix<double>& J, int axis) {
  const Eigen::Index n = J.cols() / 3;
  Eigen::SparseMatrix<double> out(J.rows(), n);
  out.reserve(J.nonZeros() / 3 + n);
  for (Eigen::Index k = 0; k < n; ++k) {
    out.startVec(k);
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, 3 * k + axis); it; ++it)
      out.insertBack(it.row(), k) = it.value();
  }
  out.finalize();
  return out;
}

Eigen::VectorXd flat(const Eigen::MatrixXd& block) {
  return Eigen::Map<const Eigen::VectorXd>(block.data(), block.size());
}
Eigen::MatrixXd unflat(const Eigen::VectorXd& v, Eigen::Index m) {
  return Eigen::Map<const Eigen::MatrixXd>(v.data(), m, 3);
}

}  // namespace

SubspaceStep::SubspaceStep(const DeformationEnergy& energy, const BasisMatrix& W) : energy_(&energy), W_(&W) {
  const double t0 = now_ms();
  const int n = W.rows(), m = W.cols();
  if (n != energy.vertex_count())
    throw Error("subspace: W has " + std::to_string(n) + " rows for a mesh of " +
                std::to_string(energy.vertex_count()) + " vertices");
  // B = (L W)^T (L W) by blocks of rows, so L W (as large as W) is never held whole.
  const Eigen::SparseMatrix<double, Eigen::RowMajor> L = energy.laplacian();
  B_ = row_gram(n, m, [&](int lo, int hi) { return laplacian_rows_times_w(L, W, lo, hi - lo); });
  precompute_ms_ = now_ms() - t0;
}

void SubspaceStep::regularize_cage(const Eigen::MatrixXd& rest_cage, double relative_weight) {
  const double t0 = now_ms();
  regularization_ = CageRegularization(basis_gram(*W_, 1, W_->rows()), rest_cage, B_.trace());
  regularization_.set_relative_weight(relative_weight);  // so the first step need not re-factor N for it
  precompute_ms_ += now_ms() - t0;
}

void SubspaceStep::refactor(const DeformationEnergy& energy) {
  const double t0 = now_ms();
  const auto& handles = energy.handle_vertices();
  if (handles.empty()) {  // N = B is singular (W 1 = 1 and L 1 = 0): nothing to solve without handles
    factored_ = false;
    return;
  }
  const int m = W_->cols();
  const Eigen::MatrixXd Wh = weighted_handle_rows(energy);
  Eigen::MatrixXd H = Wh.transpose() * Wh;
  // The bones' straightness: constant and quadratic like the handles' term.
  straightness_rows_ = energy.has_straightness_term()
                           ? Eigen::MatrixXd(energy.straightness_weight() * energy.skeleton()->offset_rows_in(*W_))
                           : Eigen::MatrixXd(m, 0);
  H.noalias() += straightness_rows_ * straightness_rows_.transpose();
  Eigen::MatrixXd N = B_ + H;
  if (regularization_.active()) N += regularization_.eps() * regularization_.penalty();
  Eigen::LLT<Eigen::MatrixXd> factor(N);
  if (factor.info() != Eigen::Success || !factor.matrixLLT().allFinite())
    throw Error(ErrorCode::NumericalFailure,
                "subspace: the preconditioner N = W^T (L^T L + w^2 Phi^T Phi) W + straightness (" + std::to_string(m) +
                    " x " + std::to_string(m) +
                    ") is not positive definite; the basis (the cage's coordinates, or the spectral modes) may be "
                    "rank-deficient, or the position weight is not positive");
  N_ = std::move(factor);
  N_matrix_ = std::move(N);
  H_ = std::move(H);
  factor_with_lines(energy, Wh);
  factored_ = true;
  forget_history();  // pairs and directions of the old handle set belong to another A
  factor_ms_ = now_ms() - t0;
}

Eigen::MatrixXd SubspaceStep::weighted_handle_rows(const DeformationEnergy& energy) const {
  const auto& handles = energy.handle_vertices();
  const Eigen::VectorXd& w = energy.handle_row_weights();
  Eigen::MatrixXd Wh = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(handles.size()), W_->cols());
  for (size_t k = 0; k < handles.size(); ++k)
    for (int j = 0; j < W_->cols(); ++j)
      Wh(static_cast<Eigen::Index>(k), j) = w[static_cast<Eigen::Index>(k)] * W_->get(handles[k], j);
  return Wh;
}

Eigen::MatrixXd SubspaceStep::along_lines_gram(const Eigen::MatrixXd& Wh, const Vertices& u) {
  const Eigen::Index m = Wh.cols();
  Eigen::MatrixXd out(3 * m, 3 * m);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      out.block(a * m, b * m, m, m) = Wh.transpose() * (u.col(a).array() * u.col(b).array()).matrix().asDiagonal() * Wh;
  return out;
}

void SubspaceStep::factor_with_lines(const DeformationEnergy& energy, const Eigen::MatrixXd& Wh) {
  with_lines_ = false;
  if (!energy.has_handle_lines()) return;
  // N (x) I3 (with_lines_ is false here) less the handle term's parts along the lines: a handle's depth is free,
  // which N (x) I3 would price as w^2 per vertex.
  Eigen::MatrixXd P = constant_matrix() - along_lines_gram(Wh, energy.line_directions());
  lines_N_.compute(P);
  lines_factored_ = energy.line_directions();
  // Only lines hold the mesh (every handle's depth free: P is singular): N (x) I3 still preconditions.
  with_lines_ = lines_N_.info() == Eigen::Success && lines_N_.matrixLLT().allFinite();
  if (with_lines_) lines_matrix_ = std::move(P);
}

Eigen::MatrixXd SubspaceStep::constant_solve(const Eigen::MatrixXd& R) const {
  return with_lines_ ? solve_stacked(lines_N_, R) : Eigen::MatrixXd(N_.solve(R));
}

void SubspaceStep::sync_options(const SolverOptions& options) {
  if (regularization_.set_relative_weight(options.cage_regularization)) refactor(*energy_);
}

Eigen::MatrixXd SubspaceStep::gradient(const EnergyJacobian& J, const EnergyEvaluation& e) const {
  Eigen::MatrixXd out;
  W_->multiply_transpose(J.gradient(e), out);
  return out;
}

Eigen::MatrixXd SubspaceStep::precondition(const Eigen::MatrixXd& R) const {
  if (!factored_) throw Error("subspace: no handles are set, so the step is undefined");
  return constant_solve(R);
}

Eigen::MatrixXd SubspaceStep::product(const EnergyJacobian& J, const Eigen::MatrixXd& V, Eigen::MatrixXd& image) const {
  W_->multiply(V, image);
  // The straightness term through its m by 7B rows here, not its #V by 7B ones on the mesh: for two bones those cost
  // as much as one pass over the bar's 28-column W, half of the product.
  const Eigen::MatrixXd Z = J.normal_product(image, EnergyJacobian::Terms::WithoutStraightness);
  Eigen::MatrixXd out;
  W_->multiply_transpose(Z, out);
  if (straightness_rows_.cols() > 0) out.noalias() += straightness_rows_ * (straightness_rows_.transpose() * V);
  return out;
}

Eigen::MatrixXd SubspaceStep::dense_jacobian(const EnergyJacobian& J, double memory_budget_bytes) const {
  const Eigen::Index n = W_->rows(), m = W_->cols();
  const auto& handles = energy_->handle_vertices();
  const Eigen::Index k = static_cast<Eigen::Index>(handles.size());
  const Eigen::Index s = straightness_rows_.cols();
  const double bytes = 8.0 * (double(3 * n + 3 * k + 3 * s) * double(3 * m) + 2.0 * double(n) * double(m));
  if (bytes > memory_budget_bytes) {
    std::ostringstream message;
    message << "exact mode needs " << static_cast<long long>(bytes / 1e6) << " MB for the dense subspace Jacobian ("
            << 3 * n << " x " << 3 * m << "), more than the budget of "
            << static_cast<long long>(memory_budget_bytes / 1e6) << " MB; use the fast mode";
    throw Error(ErrorCode::MemoryBudget, message.str());
  }
  if (W_dense_.size() == 0) W_dense_ = W_->to_dense();
  const Eigen::SparseMatrix<double> M = J.laplacian_rows_matrix();  // L (x) I3 - J_delta_hat
  Eigen::MatrixXd JW = Eigen::MatrixXd::Zero(3 * n + 3 * k + 3 * s, 3 * m);
  for (int axis = 0; axis < 3; ++axis) {
    // Row by row (row-major sparse times dense): each output row is computed alone, so blocks of rows
    // run on the thread pool with the same bits.
    const Eigen::SparseMatrix<double, Eigen::RowMajor> Ma = axis_columns(M, axis);
    parallel::parallel_for(0, static_cast<int>(3 * n), 1024, [&](int lo, int hi) {
      JW.block(lo, axis * m, hi - lo, m).noalias() = Ma.middleRows(lo, hi - lo) * W_dense_;
    });
  }
  // The handle rows w Q_h (x) W_h (Q_h = I for a point target, the projection across its line otherwise).
  const Eigen::VectorXd& w = energy_->handle_row_weights();
  for (Eigen::Index h = 0; h < k; ++h)
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::RowVector3d q = energy_->across_line(h, Eigen::RowVector3d::Unit(axis));  // row `axis` of Q_h
      for (int b = 0; b < 3; ++b) JW.block(3 * n + 3 * h + axis, b * m, 1, m) = w[h] * q[b] * W_dense_.row(handles[h]);
    }
  // The straightness rows w_s (W^T P O)^T, per axis.
  for (int axis = 0; axis < 3 && s > 0; ++axis)
    JW.block(3 * n + 3 * k + axis * s, axis * m, s, m) = straightness_rows_.transpose();
  return JW;
}

ConstrainedStep SubspaceStep::compute(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                                      const Eigen::MatrixXd& U, const SolverOptions& options) {
  if (!factored_) throw Error("subspace: no handles are set, so the step is undefined");
  sync_options(options);
  // An eye's lines turn with the targets: the lines' factor is remade (the rest of the history kept) past 2 degrees.
  if (energy_->has_handle_lines() && lines_turned(lines_factored_, energy_->line_directions()))
    factor_with_lines(*energy_, weighted_handle_rows(*energy_));
  const HardConstraints hard(*energy_, options.volume);
  const bool volume = !hard.empty();  // any hard constraint: the volume's or the skeleton's
  Eigen::MatrixXd b, c;
  const int gradient_passes = gradients(J, e, X, U, hard, b, c);
  // The skeleton's right-hand sides come from its points' rows W^T m_q, kept.
  if (hard.skeleton_count() > 0) c.rightCols(3 * hard.skeleton_count()) = hard.skeleton_gradients(e, skeleton_rows());
  const Eigen::VectorXd g = hard.values(e);
  ConstrainedStep step = options.jacobian == JacobianMode::Exact
                             ? exact_step(J, b, c, g, volume, options)
                             : fast_step(J, U, b, c, g, hard.scales(), volume,
                                         LengthCurvature(hard, e, skeleton_rows(), multipliers_), options);
  multipliers_.keep(step.lambda, energy_->skeleton_version());
  step.passes += gradient_passes;
  if (hard.skeleton_count() > 0 && step.restore.du.size() != 0)
    step.restore.point_motion = skeleton_rows().transpose() * step.restore.du;
  return step;
}

int SubspaceStep::gradients(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                            const Eigen::MatrixXd& U, const HardConstraints& hard, Eigen::MatrixXd& b,
                            Eigen::MatrixXd& c) const {
  const int Kv = hard.volume_count();
  // One transposed pass (two when 3 + 3Kv > 6 columns) serves the gradient and the volumes' right-hand sides.
  Eigen::MatrixXd G(X.rows(), 3 + 3 * Kv);
  G.leftCols(3) = J.gradient(e);
  G.rightCols(3 * Kv) = hard.volume_gradients(X);
  Eigen::MatrixXd bc;
  W_->multiply_transpose(G, bc);
  b = regularization_.active() ? Eigen::MatrixXd(bc.leftCols(3) + regularization_.gradient(U))
                               : Eigen::MatrixXd(bc.leftCols(3));
  c.resize(W_->cols(), 3 * hard.count());
  c.leftCols(3 * Kv) = bc.rightCols(3 * Kv);
  return BasisMatrix::passes(static_cast<int>(G.cols()));
}

ConstrainedStep SubspaceStep::exact_step(const EnergyJacobian& J, const Eigen::MatrixXd& b, const Eigen::MatrixXd& c,
                                         const Eigen::VectorXd& g, bool volume, const SolverOptions& options) const {
  const int m = W_->cols();
  const Eigen::Index K = c.cols() / 3;
  ConstrainedStep step;
  const Eigen::MatrixXd JW = dense_jacobian(J, options.exact_memory_budget_bytes);
  Eigen::MatrixXd A = row_gram(static_cast<int>(JW.rows()), 3 * m,
                               [&](int lo, int hi) { return Eigen::MatrixXd(JW.middleRows(lo, hi - lo)); });
  for (int axis = 0; axis < 3 && regularization_.active(); ++axis)
    A.block(axis * m, axis * m, m, m) += regularization_.eps() * regularization_.penalty();
  // Handles that are single vertices leave rotations about them free (A only semidefinite); a relative
  // 1e-12 shift keeps the factorization defined and changes the step by about that much (as in the full space).
  A.diagonal().array() += 1e-12 * A.diagonal().cwiseAbs().mean();
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive())
    throw Error(ErrorCode::NumericalFailure,
                "exact subspace step: the normal matrix (J_f W)^T (J_f W) could not be factored");
  Eigen::MatrixXd rhs(3 * m, volume ? 1 + K : 1);
  rhs.col(0) = flat(b);
  if (volume)
    for (Eigen::Index k = 0; k < K; ++k) rhs.col(1 + k) = flat(c.middleCols(3 * k, 3));
  const Eigen::MatrixXd sol = ldlt.solve(rhs);
  const Eigen::MatrixXd u = unflat(sol.col(0), m);
  Eigen::MatrixXd V(m, volume ? 3 * K : 0);
  if (volume)
    for (Eigen::Index k = 0; k < K; ++k) V.middleCols(3 * k, 3) = unflat(sol.col(1 + k), m);
  step.lambda = volume ? volume_multipliers(u, V, c, g) : Eigen::VectorXd(Eigen::VectorXd::Zero(K));
  step.du = volume ? Eigen::MatrixXd(-add_blocks(u, V, step.lambda)) : Eigen::MatrixXd(-u);
  step.slope = block_dot(step.du, add_blocks(b, c, step.lambda));
  // One forward pass maps the step and the restoration directions N^-1 c_k.
  Eigen::MatrixXd D(m, volume ? 3 + 3 * K : 3), image;
  D.leftCols(3) = step.du;
  if (volume) D.rightCols(3 * K) = constant_solve(c);
  W_->multiply(D, image);
  step.passes += BasisMatrix::passes(static_cast<int>(D.cols()));
  step.dx = image.leftCols(3);
  if (volume) {
    step.restore.du = D.rightCols(3 * K);
    step.restore.dx = std::make_shared<const Eigen::MatrixXd>(image.rightCols(3 * K));
  }
  return step;
}

ConstrainedStep SubspaceStep::fast_step(const EnergyJacobian& J, const Eigen::MatrixXd& U, const Eigen::MatrixXd& b,
                                        const Eigen::MatrixXd& c, const Eigen::VectorXd& g,
                                        const Eigen::VectorXd& scales, bool volume, const LengthCurvature& curvature,
                                        const SolverOptions& options) {
  PcgStepProblem problem;
  problem.product = [&](const Eigen::MatrixXd& P, Eigen::MatrixXd& image) {
    Eigen::MatrixXd AP = product(J, P, image);
    if (regularization_.active()) AP += regularization_.hessian_times(P);
    return AP;
  };
  problem.curvature = curvature.term();
  problem.base_preconditioner = base_preconditioner(U, options);
  const bool factored = gauss_newton_.ready();  // the factor serves this step (record_products may drop it)
  problem.image_rows = W_->rows();
  problem.first_run_products = products_before_factor(options);
  std::unique_ptr<ProjectedPcg> pcg;
  ConstrainedStep step = pcg_step(problem, memory_, b, c, g, scales, volume, options, pcg);
  record_products(step.products);
  step.passes = 2 * step.products;
  if (volume && factored) {
    // Restoring along the factor's P^-1 c made solves creep (method.md section 11.1): restore along N^-1 c.
    set_restoration(constant_solve(c), nullptr, step);
  } else if (volume) {
    set_restoration(pcg->constraint_direction(), pcg->constraint_image_known() ? &pcg->constraint_image() : nullptr,
                    step);
  }
  return step;
}

const Eigen::MatrixXd& SubspaceStep::skeleton_rows() {
  static const Eigen::MatrixXd none;
  const SkeletonConstraints* skeleton = energy_->skeleton();
  if (!skeleton) return none;
  const Eigen::MatrixXd& rows = skeleton->rows_in(*W_);
  if (skeleton_rest_version_ != energy_->skeleton_version()) {
    if (U0_.size() != 0) skeleton_rest_ = skeleton->points(energy_->rest_positions()) - rows.transpose() * U0_;
    skeleton_rest_version_ = energy_->skeleton_version();
  }
  return rows;
}

std::optional<Eigen::MatrixXd> SubspaceStep::skeleton_points(const Eigen::MatrixXd& U) {
  if (!energy_->skeleton() || U0_.size() == 0) return std::nullopt;
  const Eigen::MatrixXd& rows = skeleton_rows();
  return Eigen::MatrixXd(skeleton_rest_ + rows.transpose() * U);
}

Eigen::MatrixXd SubspaceStep::constant_matrix() const {
  if (with_lines_) return lines_matrix_;
  const Eigen::Index m = N_matrix_.rows();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(3 * m, 3 * m);
  for (int axis = 0; axis < 3; ++axis) out.block(axis * m, axis * m, m, m) = N_matrix_;
  return out;
}

double SubspaceStep::factor_cost(double K) const {
  // The factor's cost in products: R's two sums of 3 rows per vertex (27 K m^2 multiply-adds) and the Cholesky
  // factor (9 m^3), against a product's two passes over W (n m each, 3 columns) at a time per multiply-add about 7
  // times a dense one's (measured natively on the hand bones: a factor with K = 235 about 200 ms, a product 2.6 ms).
  constexpr double kDenseToStreaming = 0.15;
  const double n = W_->rows(), m = W_->cols();
  return kDenseToStreaming * (27.0 * K * m * m + 9.0 * m * m * m) / (n * m);
}

bool SubspaceStep::factor_wanted(const SolverOptions& options) const {
  return options.preconditioner == Preconditioner::GaussNewton && rotation_terms_ &&
         W_->cols() <= GaussNewtonFactor::kMaxUnknownsPerAxis;
}

bool SubspaceStep::factor_pays() {
  // The cost without R first, so that a model on which N does well never asks for the stiff vertices.
  return gauss_newton_.debt() >= factor_cost(0) && gauss_newton_.due(factor_cost(rotation_vertex_count_(true)));
}

int SubspaceStep::products_before_factor(const SolverOptions& options) {
  if (!factor_wanted(options)) return std::numeric_limits<int>::max();
  // Before factor_pays would look for the stiff vertices, their upper bound: the cap is then never too tight.
  const double cost = factor_cost(rotation_vertex_count_(gauss_newton_.debt() >= factor_cost(0)));
  return gauss_newton_.products_before(std::max(factor_cost(0), gauss_newton_.price(cost)));
}

std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> SubspaceStep::base_preconditioner(const Eigen::MatrixXd& U,
                                                                                         const SolverOptions& options) {
  if (!factor_wanted(options)) {
    gauss_newton_.clear();
    return [this](const Eigen::MatrixXd& R) { return constant_solve(R); };
  }
  if (factor_pays()) gauss_newton_.factor(constant_matrix() + rotation_terms_(U));
  if (!gauss_newton_.ready()) return [this](const Eigen::MatrixXd& R) { return constant_solve(R); };
  return [this](const Eigen::MatrixXd& R) { return gauss_newton_.solve(R); };
}

void SubspaceStep::set_restoration(const Eigen::MatrixXd& d, const Eigen::MatrixXd* image, ConstrainedStep& step) {
  // Any directions d_k with an invertible C^T D restore the volumes (restore_volume solves for the coefficients
  // along them); M^-1 c_k change the energy least, and those of a recent step almost as little. Reusing them
  // while each turns by less than ~8 degrees saves a pass over W in most interactive frames; the fixed point is
  // unaffected (at convergence the restoring moves vanish).
  const auto turned = [&] {
    if (restore_du_.size() != d.size()) return true;
    for (Eigen::Index k = 0; k < d.cols() / 3; ++k) {
      const Eigen::MatrixXd a = d.middleCols(3 * k, 3), r = restore_du_.middleCols(3 * k, 3);
      if (!(block_dot(a, r) / std::sqrt(a.squaredNorm() * r.squaredNorm()) > 0.99)) return true;
    }
    return false;
  };
  if (image) {
    restore_du_ = d;
    restore_dx_ = std::make_shared<const Eigen::MatrixXd>(*image);
  } else if (turned()) {
    restore_du_ = d;
    Eigen::MatrixXd mapped;
    W_->multiply(restore_du_, mapped);
    restore_dx_ = std::make_shared<const Eigen::MatrixXd>(std::move(mapped));
    step.passes += BasisMatrix::passes(static_cast<int>(d.cols()));
  }
  step.restore.du = restore_du_;
  step.restore.dx = restore_dx_;
}

}  // namespace sd
