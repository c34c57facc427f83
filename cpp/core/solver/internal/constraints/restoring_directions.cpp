#include "core/solver/internal/constraints/restoring_directions.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/solver/internal/constraints/direction_blocks.h"
#include "core/solver/internal/constraints/hard_constraints.h"

namespace sd {
namespace {

// Relative error below which a linear constraint counts as held: a step keeps it to rounding (about 1e-16).
constexpr double kLinearHeld = 1e-12;

// The blocks of R combined by P: block l of the result is sum_k P(k, l) block k of R.
Eigen::MatrixXd combine(const Eigen::MatrixXd& R, const Eigen::MatrixXd& P) {
  Eigen::MatrixXd out(R.rows(), 3 * P.cols());
  for (int axis = 0; axis < 3; ++axis) axis_columns(out, axis).noalias() = axis_columns(R, axis) * P;
  return out;
}

}  // namespace

void NonlinearRestoration::next_step(const RestoringDirections& step) {
  kept_ = step.dx && step.dx == last_step_;
  last_step_ = step.dx;
}

const RestoringDirections* NonlinearRestoration::for_trial(const HardConstraints& hard, const RestoringDirections& step,
                                                           const Vertices& X, const Eigen::MatrixXd& points,
                                                           const Eigen::VectorXd& g) {
  std::vector<int> nonlinear = hard.nonlinear();
  if (!kept_ || step.empty() || nonlinear.empty() || static_cast<int>(nonlinear.size()) == hard.count()) return nullptr;
  for (Eigen::Index k = 0; k < g.size(); ++k)
    if (std::find(nonlinear.begin(), nonlinear.end(), k) == nonlinear.end() &&
        !(std::abs(g[k]) <= kLinearHeld * hard.scales()[k]))
      return nullptr;
  const DeformationEnergy& energy = hard.energy();
  if (source_ == step.dx && &energy == energy_ && energy.skeleton_version() == skeleton_version_ &&
      nonlinear == nonlinear_)
    return usable_ ? &combined_ : nullptr;
  return make(hard, step, X, points, std::move(nonlinear));
}

const RestoringDirections* NonlinearRestoration::make(const HardConstraints& hard, const RestoringDirections& step,
                                                      const Vertices& X, const Eigen::MatrixXd& points,
                                                      std::vector<int> nonlinear) {
  source_ = step.dx;
  energy_ = &hard.energy();
  skeleton_version_ = energy_->skeleton_version();
  nonlinear_ = std::move(nonlinear);
  // S = C^T R at X (one pass over the triangles for the volume's rows).
  const HardConstraints::Along along(hard, X, *step.dx, step.point_motion, points);
  const Eigen::MatrixXd S = along.slopes(Eigen::VectorXd::Zero(hard.count()));
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(S);
  usable_ = S.allFinite() && lu.isInvertible();
  if (!usable_) return nullptr;
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(hard.count(), static_cast<Eigen::Index>(nonlinear_.size()));
  for (size_t l = 0; l < nonlinear_.size(); ++l) E(nonlinear_[l], static_cast<Eigen::Index>(l)) = 1.0;
  const Eigen::MatrixXd P = lu.solve(E);
  combined_.du = combine(step.du, P);
  combined_.dx = std::make_shared<const Eigen::MatrixXd>(combine(*step.dx, P));
  combined_.point_motion = step.point_motion.size() ? combine(step.point_motion, P) : Eigen::MatrixXd();
  combined_.driven = nonlinear_;
  usable_ = P.allFinite() && combined_.dx->allFinite();
  return usable_ ? &combined_ : nullptr;
}

}  // namespace sd
