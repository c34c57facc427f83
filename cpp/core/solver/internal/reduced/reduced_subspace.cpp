#include "core/solver/internal/reduced/reduced_subspace.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/solver/internal/constraints/hard_constraints.h"
#include "core/solver/internal/steps/pcg_step.h"
#include "core/solver/internal/two_lane_kernels.h"

namespace sd {
namespace {

Eigen::VectorXd flat(const Eigen::MatrixXd& block) {
  return Eigen::Map<const Eigen::VectorXd>(block.data(), block.size());
}
Eigen::MatrixXd unflat(const Eigen::VectorXd& v, Eigen::Index m) {
  return Eigen::Map<const Eigen::MatrixXd>(v.data(), m, 3);
}

// Whether the directions d (m by 3K) differ from the kept ones by more than about 8 degrees in any block.
bool turned(const Eigen::MatrixXd& kept, const Eigen::MatrixXd& d) {
  if (kept.rows() != d.rows() || kept.cols() != d.cols()) return true;
  for (Eigen::Index k = 0; k < d.cols() / 3; ++k) {
    const Eigen::MatrixXd a = d.middleCols(3 * k, 3), r = kept.middleCols(3 * k, 3);
    if (!(block_dot(a, r) / std::sqrt(a.squaredNorm() * r.squaredNorm()) > 0.99)) return true;
  }
  return false;
}

// H V for each m by 3 block of V: the handle Gram matrix acts on x, y and z alike.
Eigen::MatrixXd per_axis(const Eigen::MatrixXd& H, const Eigen::MatrixXd& V) {
  return two_lane::matrix_times_block(H, V);
}

}  // namespace

ReducedSubspace::ReducedSubspace(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                                 SubspaceStep& subspace, std::unique_ptr<ReducedLaplacianTerm> rule)
    : energy_(&energy), W_(&W), U0_(U0), subspace_(&subspace), rule_(std::move(rule)) {}

EnergyEvaluation ReducedSubspace::evaluate(const Vertices& X, const Eigen::MatrixXd& U) const {
  EnergyEvaluation e;
  rule_->evaluate(U, e);
  e.constraint = energy_->constraints(X, &e.volume);
  energy_->evaluate_skeleton(X, e, subspace_->skeleton_points(U));
  energy_->update_position_terms(X, e);
  return e;
}

void ReducedSubspace::linearize(const Eigen::MatrixXd& U) { rule_->linearize(U); }

Eigen::MatrixXd ReducedSubspace::handle_gradient(const Eigen::MatrixXd& U) {
  if (G_version_ != energy_->handle_terms_version()) update_handle_pull();
  Eigen::MatrixXd out = subspace_->handle_gram() * U - G_;
  if (energy_->has_handle_lines()) {
    // Less the offsets' parts along the lines: x_k - v_k = x0_k + W_k (U - U0) - v_k for each handle vertex k.
    const Eigen::MatrixXd D = U - U0_;
    out -= along_lines(
        [&](Eigen::Index row, const Eigen::RowVector3d& moved) {
          const int k = handle_rows_[static_cast<size_t>(row)];
          return Eigen::RowVector3d(energy_->rest_positions().row(k) + moved - energy_->targets().row(row));
        },
        D);
  }
  return out;
}

Eigen::MatrixXd ReducedSubspace::along_lines(
    const std::function<Eigen::RowVector3d(Eigen::Index, const Eigen::RowVector3d&)>& offset,
    const Eigen::MatrixXd& V) const {
  // sum_k w_k^2 W_k^T ((o_k . u_k) u_k), o_k = offset(k, W_k V), group by group (only the handles' rows of W).
  const Eigen::VectorXd& w = energy_->handle_row_weights();
  const Vertices& u = energy_->line_directions();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(W_->cols(), 3);
  Eigen::Index start = 0;
  for (size_t g = 0; g < W_groups_.size(); ++g) {
    const Eigen::Index size = group_sizes_[g];
    Eigen::MatrixXd image, part;
    W_groups_[g].multiply(V, image);
    for (Eigen::Index r = 0; r < size; ++r) {
      const Eigen::Index row = start + r;
      const Eigen::RowVector3d o = offset(row, image.row(r));
      image.row(r) = w[row] * w[row] * o.dot(u.row(row)) * u.row(row);
    }
    W_groups_[g].multiply_transpose(image, part);
    out += part;
    start += size;
  }
  return out;
}

void ReducedSubspace::update_handle_pull() {
  const auto& handles = energy_->handle_vertices();
  const auto& sizes = energy_->handle_group_sizes();
  if (handles != handle_rows_ || sizes != group_sizes_) {
    handle_rows_ = handles;
    group_sizes_ = sizes;
    W_groups_.clear();
    size_t start = 0;
    for (int size : sizes) {
      W_groups_.push_back(W_->select_rows(std::vector<int>(handles.begin() + start, handles.begin() + start + size)));
      start += static_cast<size_t>(size);
    }
    G_groups_.assign(sizes.size(), Eigen::MatrixXd());
  }
  // With X = X0 + W (U - U0) the residual w_k (x_k - v_k) is w_k (W_k U - (v_k - x0_k + W_k U0)); fold the
  // constants into G so that the gradient is exactly H U - G.
  const Eigen::VectorXd& w = energy_->handle_row_weights();
  Eigen::MatrixXd pulled(static_cast<Eigen::Index>(handles.size()), 3);
  for (size_t k = 0; k < handles.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    pulled.row(row) = w[row] * w[row] * (energy_->targets().row(row) - energy_->rest_positions().row(handles[k]));
  }
  G_ = subspace_->handle_gram() * U0_;
  Eigen::Index start = 0;
  for (size_t g = 0; g < group_sizes_.size(); ++g) {
    const Eigen::Index size = group_sizes_[g];
    const bool same = G_groups_[g].size() != 0 && pulled_.rows() == pulled.rows() &&
                      pulled_.middleRows(start, size) == pulled.middleRows(start, size);
    if (!same) W_groups_[g].multiply_transpose(pulled.middleRows(start, size), G_groups_[g]);
    G_ += G_groups_[g];
    start += size;
  }
  pulled_ = std::move(pulled);
  G_version_ = energy_->handle_terms_version();
}

Eigen::MatrixXd ReducedSubspace::gradient(const EnergyEvaluation& e, const Eigen::MatrixXd& U) {
  return handle_gradient(U) + rule_->gradient(e);
}

namespace {

// The largest over the constraints (3-column blocks) of |G_k - G0_k| / |G0_k|.
double largest_tilt(const Eigen::MatrixXd& G, const Eigen::MatrixXd& G0) {
  double tilt = 0.0;
  for (Eigen::Index k = 0; k < G.cols() / 3; ++k) {
    const double t = (G.middleCols(3 * k, 3) - G0.middleCols(3 * k, 3)).norm() / G0.middleCols(3 * k, 3).norm();
    if (!std::isfinite(t)) return std::numeric_limits<double>::infinity();  // a part whose gradient was zero
    tilt = std::max(tilt, t);
  }
  return tilt;
}

}  // namespace

const Eigen::MatrixXd& ReducedSubspace::volume_directions(const Vertices& X, bool may_lag, bool& made) {
  Eigen::MatrixXd gradients = energy_->constraint_gradients(X);  // O(#V): no pass over W
  made = !(may_lag && volume_c_parts_ == energy_->volume_parts_version() &&
           volume_c_gradients_.rows() == gradients.rows() && volume_c_gradients_.cols() == gradients.cols() &&
           largest_tilt(gradients, volume_c_gradients_) <= kLaggedTilt);
  if (made) {
    W_->multiply_transpose(gradients, volume_c_);
    volume_c_gradients_ = std::move(gradients);
    volume_c_parts_ = energy_->volume_parts_version();
  }
  return volume_c_;
}

Eigen::MatrixXd ReducedSubspace::product(const Eigen::MatrixXd& V) const {
  Eigen::MatrixXd out = rule_->product(V);
  out += per_axis(subspace_->handle_gram(), V);
  if (energy_->has_handle_lines())
    for (Eigen::Index t = 0; t < V.cols() / 3; ++t)
      out.middleCols(3 * t, 3) -=
          along_lines([](Eigen::Index, const Eigen::RowVector3d& o) { return o; }, V.middleCols(3 * t, 3));
  if (subspace_->regularization().active()) out += subspace_->regularization().hessian_times(V);
  return out;
}

Eigen::MatrixXd ReducedSubspace::dense_matrix() const {
  const Eigen::Index m = W_->cols();
  Eigen::MatrixXd A = rule_->dense_matrix();
  for (int axis = 0; axis < 3; ++axis) {
    A.block(axis * m, axis * m, m, m) += subspace_->handle_gram();
    if (subspace_->regularization().active())
      A.block(axis * m, axis * m, m, m) += subspace_->regularization().eps() * subspace_->regularization().penalty();
  }
  if (energy_->has_handle_lines())  // less the handle term's parts along the lines, as the subspace's factor
    A -= SubspaceStep::along_lines_gram(subspace_->weighted_handle_rows(*energy_), energy_->line_directions());
  return A;
}

ConstrainedStep ReducedSubspace::exact_step(const Eigen::MatrixXd& b, const Eigen::MatrixXd& c,
                                            const Eigen::VectorXd& g, bool volume) const {
  const Eigen::Index m = W_->cols(), K = c.cols() / 3;
  Eigen::MatrixXd A = dense_matrix();
  A.diagonal().array() += 1e-12 * A.diagonal().cwiseAbs().mean();  // as the subspace's exact step
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive())
    throw Error(ErrorCode::NumericalFailure, "exact reduced step: the reduced normal matrix could not be factored");
  Eigen::MatrixXd rhs(3 * m, volume ? 1 + K : 1);
  rhs.col(0) = flat(b);
  for (Eigen::Index k = 0; volume && k < K; ++k) rhs.col(1 + k) = flat(c.middleCols(3 * k, 3));
  const Eigen::MatrixXd sol = ldlt.solve(rhs);
  const Eigen::MatrixXd u = unflat(sol.col(0), m);
  Eigen::MatrixXd V(m, volume ? 3 * K : 0);
  for (Eigen::Index k = 0; volume && k < K; ++k) V.middleCols(3 * k, 3) = unflat(sol.col(1 + k), m);
  ConstrainedStep step;
  step.lambda = volume ? volume_multipliers(u, V, c, g) : Eigen::VectorXd(Eigen::VectorXd::Zero(K));
  step.du = volume ? Eigen::MatrixXd(-add_blocks(u, V, step.lambda)) : Eigen::MatrixXd(-u);
  step.slope = block_dot(step.du, add_blocks(b, c, step.lambda));
  return step;
}

ConstrainedStep ReducedSubspace::step(const EnergyEvaluation& e, const Vertices& X, const Eigen::MatrixXd& U,
                                      const SolverOptions& options) {
  if (!subspace_->factored()) throw Error("subspace: no handles are set, so the step is undefined");
  subspace_->sync_options(options);
  linearize(U);
  const HardConstraints hard(*energy_, options.volume);
  Eigen::MatrixXd b = gradient(e, U);
  if (subspace_->regularization().active()) b += subspace_->regularization().gradient(U);
  Eigen::MatrixXd c(W_->cols(), 3 * hard.count());
  // A drag's frame: other targets than the last step's (compared by value: an app may send the same ones again).
  const Vertices& targets = energy_->targets();
  const bool moving = targets.rows() != last_step_targets_.rows() || targets != last_step_targets_;
  last_step_targets_ = targets;
  bool volume_pass = false;
  if (hard.volume_count() > 0)
    c.leftCols(3 * hard.volume_count()) =
        volume_directions(X, moving && options.jacobian == JacobianMode::Fast, volume_pass);
  ConstrainedStep step = solve_step(e, U, b, c, hard, options);
  step.lagged = hard.volume_count() > 0 && !volume_pass;
  step.passes += volume_pass ? BasisMatrix::passes(3 * hard.volume_count()) : 0;
  return step;
}

ConstrainedStep ReducedSubspace::finishing_step(const EnergyJacobian& J, const EnergyEvaluation& e, const Vertices& X,
                                                const Eigen::MatrixXd& U, const SolverOptions& options) {
  if (!subspace_->factored()) throw Error("subspace: no handles are set, so the step is undefined");
  subspace_->sync_options(options);
  linearize(U);
  const HardConstraints hard(*energy_, options.volume);
  // The subspace step's right-hand sides: the full energy's gradient and the volumes' c, made anew.
  Eigen::MatrixXd b, c;
  const int gradient_passes = subspace_->gradients(J, e, X, U, hard, b, c);
  ConstrainedStep step = solve_step(e, U, b, c, hard, options);
  step.passes += gradient_passes;
  return step;
}

ConstrainedStep ReducedSubspace::solve_step(const EnergyEvaluation& e, const Eigen::MatrixXd& U,
                                            const Eigen::MatrixXd& b, Eigen::MatrixXd& c, const HardConstraints& hard,
                                            const SolverOptions& options) {
  const bool volume = !hard.empty();  // any hard constraint: the volume's or the skeleton's
  if (hard.skeleton_count() > 0)
    c.rightCols(3 * hard.skeleton_count()) = hard.skeleton_gradients(e, subspace_->skeleton_rows());
  const Eigen::VectorXd g = hard.values(e);
  ConstrainedStep step;
  if (options.jacobian == JacobianMode::Exact) {
    step = exact_step(b, c, g, volume);
  } else {
    PcgStepProblem problem;
    problem.product = [&](const Eigen::MatrixXd& V, Eigen::MatrixXd& image) {
      image.resize(0, V.cols());
      return product(V);
    };
    // The subspace step's (section 11.1): the rule approximates the same A.
    problem.base_preconditioner = subspace_->base_preconditioner(U, options);
    const LengthCurvature curvature(hard, e, subspace_->skeleton_rows(), subspace_->multipliers());
    problem.curvature = curvature.term();
    std::unique_ptr<ProjectedPcg> pcg;
    step = pcg_step(problem, memory_, b, c, g, hard.scales(), volume, options, pcg);
    // Its products read no W: they cost the factor's debt only their share of one over W.
    subspace_->record_products(step.products,
                               rule_->product_cost() / (6.0 * static_cast<double>(W_->rows()) * W_->cols()), false);
  }
  subspace_->multipliers().keep(step.lambda, energy_->skeleton_version());
  // One forward pass maps the step and, when they turned, the restoring directions N^-1 c_k (any direction with
  // c.d != 0 restores the volume; one that turned by less than about 8 degrees since the last pass keeps its
  // image, so most frames of a drag map three columns instead of six).
  const Eigen::MatrixXd d = volume ? subspace_->precondition(c) : Eigen::MatrixXd();
  const bool remap = volume && turned(restore_du_, d);
  Eigen::MatrixXd D(W_->cols(), remap ? 3 + 3 * hard.count() : 3), image;
  D.leftCols(3) = step.du;
  if (remap) D.rightCols(3 * hard.count()) = d;
  W_->multiply(D, image);
  step.dx = image.leftCols(3);
  if (remap) {
    restore_du_ = d;
    restore_dx_ = std::make_shared<const Eigen::MatrixXd>(image.rightCols(3 * hard.count()));
  }
  if (volume) {
    step.restore.du = restore_du_;
    step.restore.dx = restore_dx_;
    if (hard.skeleton_count() > 0) step.restore.point_motion = subspace_->skeleton_rows().transpose() * restore_du_;
  }
  step.passes = BasisMatrix::passes(static_cast<int>(D.cols()));  // the forward map
  return step;
}

}  // namespace sd
